// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "dform/core/polyline.h"

namespace dform {
namespace {

Status invalidCurve(std::string message) { return {ErrorCode::InputInvalid, std::move(message)}; }

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Places w to the left of the directed segment p -> q at distance a from p and b from q.
Eigen::Vector2d placeLeft(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double a, double b) {
  const double d = (q - p).norm();
  const Eigen::Vector2d along = (q - p) / d;
  const Eigen::Vector2d left(-along.y(), along.x());
  const double x = (a * a - b * b + d * d) / (2.0 * d);
  // a^2 - x^2 dips below 0 only by rounding for a valid (possibly flat) triangle.
  const double y = std::sqrt(std::max(0.0, a * a - x * x));
  return p + x * along + y * left;
}

}  // namespace

Result<Points2> unfoldDisc(const Points3& V, const Faces& F) {
  const Eigen::Index nV = V.rows(), nF = F.rows();
  if (nV < 3 || nF != nV - 2)
    return invalidCurve("cannot unfold: a disc without interior vertices on " + std::to_string(nV) +
                        " vertices has " + std::to_string(std::max<Eigen::Index>(nV - 2, 0)) +
                        " triangles, not " + std::to_string(nF));
  std::map<std::pair<int, int>, int> faceOfEdge;  // directed edge -> face
  std::vector<bool> used(std::size_t(nV), false);
  for (Eigen::Index f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) {
      const int u = F(f, c), v = F(f, (c + 1) % 3);
      if (u < 0 || u >= nV || v < 0 || v >= nV || u == v)
        return invalidCurve("cannot unfold: triangle " + std::to_string(f) +
                            " has a bad vertex index");
      if (!faceOfEdge.emplace(std::make_pair(u, v), int(f)).second)
        return invalidCurve("cannot unfold: edge " + std::to_string(u) + "-" + std::to_string(v) +
                            " is used twice the same way (faces not consistently oriented)");
      used[std::size_t(u)] = true;
    }
  for (Eigen::Index v = 0; v < nV; ++v)
    if (!used[std::size_t(v)])
      return invalidCurve("cannot unfold: vertex " + std::to_string(v) + " is unused");

  auto edgeLength = [&](int u, int v) { return (V.row(u) - V.row(v)).norm(); };
  Points2 flat = Points2::Zero(nV, 2);
  std::vector<bool> placed(std::size_t(nV), false), visited(std::size_t(nF), false);
  const int p0 = F(0, 0), p1 = F(0, 1), p2 = F(0, 2);
  flat.row(p1) = Eigen::RowVector2d(edgeLength(p0, p1), 0.0);
  flat.row(p2) = placeLeft(flat.row(p0), flat.row(p1), edgeLength(p0, p2), edgeLength(p1, p2));
  placed[std::size_t(p0)] = placed[std::size_t(p1)] = placed[std::size_t(p2)] = true;
  visited[0] = true;
  std::deque<int> queue{0};
  Eigen::Index visitedCount = 1;
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    for (int c = 0; c < 3; ++c) {
      const int u = F(f, c), v = F(f, (c + 1) % 3);
      const auto it = faceOfEdge.find({v, u});
      if (it == faceOfEdge.end() || visited[std::size_t(it->second)]) continue;
      const int g = it->second;
      int w = -1;
      for (int k = 0; k < 3; ++k)
        if (F(g, k) != u && F(g, k) != v) w = F(g, k);
      // In a disc whose vertices all lie on the boundary, each vertex's faces form one path of the
      // dual tree, so a vertex reached again through the tree was already placed from this side.
      if (w < 0 || placed[std::size_t(w)])
        return invalidCurve(
            "cannot unfold: the triangles do not form a disc without interior vertices");
      // g runs v -> u -> w counter-clockwise, so w lies to the left of v -> u.
      flat.row(w) = placeLeft(flat.row(v), flat.row(u), edgeLength(v, w), edgeLength(u, w));
      placed[std::size_t(w)] = true;
      visited[std::size_t(g)] = true;
      ++visitedCount;
      queue.push_back(g);
    }
  }
  if (visitedCount != nF)
    return invalidCurve("cannot unfold: the triangles are not connected across edges");
  return flat;
}

Status checkSheet(const Points2& outline, const std::string& pieceName) {
  const auto crossing = findSelfIntersection(outline);
  if (!crossing) return Status::ok();
  const int n = int(outline.rows());
  auto edge = [n](int i) { return std::to_string(i + 1) + "-" + std::to_string((i + 1) % n + 1); };
  return invalidCurve("piece " + pieceName + " unfolds onto itself near curve points " +
                      edge(crossing->first) + " and " + edge(crossing->second) +
                      ": it cannot be cut from one sheet");
}

Points3 mapBarycentric(const Points2& flat, const Points3& shape, const Faces& F,
                       const Points2& query) {
  const Eigen::Index nF = F.rows(), nQ = query.rows();
  Points3 out(nQ, 3);
  if (nF == 0) return out.setZero();

  // Uniform grid over the bounding box, about one triangle per cell.
  const Eigen::Vector2d lo = flat.colwise().minCoeff(), hi = flat.colwise().maxCoeff();
  const int cells = std::max(1, int(std::ceil(std::sqrt(double(nF)))));
  const Eigen::Vector2d size = (hi - lo).cwiseMax(std::numeric_limits<double>::min());
  auto cellOf = [&](const Eigen::Vector2d& p, int axis) {
    const double t = (p(axis) - lo(axis)) / size(axis) * cells;
    return std::clamp(int(std::floor(t)), 0, cells - 1);
  };
  std::vector<std::vector<int>> grid(std::size_t(cells) * std::size_t(cells));
  for (Eigen::Index f = 0; f < nF; ++f) {
    Eigen::Vector2d fmin = flat.row(F(f, 0)), fmax = fmin;
    for (int c = 1; c < 3; ++c) {
      fmin = fmin.cwiseMin(Eigen::Vector2d(flat.row(F(f, c))));
      fmax = fmax.cwiseMax(Eigen::Vector2d(flat.row(F(f, c))));
    }
    for (int gx = cellOf(fmin, 0); gx <= cellOf(fmax, 0); ++gx)
      for (int gy = cellOf(fmin, 1); gy <= cellOf(fmax, 1); ++gy)
        grid[std::size_t(gx) * std::size_t(cells) + std::size_t(gy)].push_back(int(f));
  }

  // Barycentric coordinates (of corners 1 and 2; corner 0 gets the rest) and how far inside.
  auto coordinates = [&](int f, const Eigen::Vector2d& p, double& l1, double& l2) {
    const Eigen::Vector2d a = flat.row(F(f, 0)), b = flat.row(F(f, 1)), c = flat.row(F(f, 2));
    const double d = cross2(b - a, c - a);
    l1 = cross2(p - a, c - a) / d;
    l2 = cross2(b - a, p - a) / d;
    const double inside = std::min({1.0 - l1 - l2, l1, l2});
    return std::isfinite(inside) ? inside : -std::numeric_limits<double>::infinity();
  };
  for (Eigen::Index q = 0; q < nQ; ++q) {
    const Eigen::Vector2d p = query.row(q);
    int best = -1;
    double bestInside = -std::numeric_limits<double>::infinity(), b1 = 0.0, b2 = 0.0;
    auto consider = [&](int f) {
      double l1, l2;
      const double inside = coordinates(f, p, l1, l2);
      if (best < 0 || inside > bestInside) best = f, bestInside = inside, b1 = l1, b2 = l2;
    };
    for (int f : grid[std::size_t(cellOf(p, 0)) * std::size_t(cells) + std::size_t(cellOf(p, 1))])
      consider(f);
    // Not inside any triangle of its cell beyond rounding: outside the mesh, search them all.
    const double roundingSlack = 1e-12;  // barycentric coordinates are relative: ~1e4 ulps
    if (bestInside < -roundingSlack)
      for (Eigen::Index f = 0; f < nF; ++f) consider(int(f));
    // A query on a vertex takes that vertex exactly (the formula would too, barring contraction).
    bool exact = false;
    for (int c = 0; c < 3 && !exact; ++c)
      if (flat.row(F(best, c)) == query.row(q)) out.row(q) = shape.row(F(best, c)), exact = true;
    if (!exact)
      out.row(q) = (1.0 - b1 - b2) * shape.row(F(best, 0)) + b1 * shape.row(F(best, 1)) +
                   b2 * shape.row(F(best, 2));
  }
  return out;
}

}  // namespace dform
