// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact_placement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace dform {

namespace {

// Anchors of a region spread less than this (ratio of the spread's two eigenvalues: 1e-5 of its
// size across) lie in a line for the fit.
constexpr double kAnchorSpread = 1e-10;

// A region whose anchors lie off one plane by more than this (of the piece's size) is traced.
constexpr double kPlaneMisfit = 1e-9;

// The regions of a piece between its constrained edges (followed folds, the seam): each region's
// vertices, sorted.
std::vector<std::vector<int>> regionsBetween(const Faces& F,
                                             const std::vector<std::vector<int>>& constrained) {
  const Eigen::Index nF = F.rows();
  std::set<std::pair<int, int>> walls;
  for (const std::vector<int>& line : constrained)
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      walls.insert(std::minmax(line[k], line[k + 1]));
  // Each face's three sides, sorted by their ends: a side's two faces are neighbours in the
  // list.
  std::vector<std::pair<std::pair<int, int>, Eigen::Index>> sides;
  sides.reserve(std::size_t(3 * nF));
  for (Eigen::Index f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) sides.push_back({std::minmax(F(f, c), F(f, (c + 1) % 3)), f});
  std::sort(sides.begin(), sides.end());
  std::vector<std::vector<Eigen::Index>> neighbours(static_cast<std::size_t>(nF));
  for (std::size_t k = 0; k + 1 < sides.size(); ++k)
    if (sides[k].first == sides[k + 1].first && !walls.count(sides[k].first)) {
      neighbours[std::size_t(sides[k].second)].push_back(sides[k + 1].second);
      neighbours[std::size_t(sides[k + 1].second)].push_back(sides[k].second);
    }
  std::vector<int> region(std::size_t(nF), -1);
  std::vector<std::vector<int>> members;
  for (Eigen::Index seed = 0; seed < nF; ++seed) {
    if (region[std::size_t(seed)] >= 0) continue;
    const int id = int(members.size());
    members.emplace_back();
    std::vector<Eigen::Index> stack{seed};
    region[std::size_t(seed)] = id;
    while (!stack.empty()) {
      const Eigen::Index f = stack.back();
      stack.pop_back();
      for (int c = 0; c < 3; ++c) members.back().push_back(F(f, c));
      for (Eigen::Index other : neighbours[std::size_t(f)])
        if (region[std::size_t(other)] < 0) {
          region[std::size_t(other)] = id;
          stack.push_back(other);
        }
    }
    std::sort(members.back().begin(), members.back().end());
    members.back().erase(std::unique(members.back().begin(), members.back().end()),
                         members.back().end());
  }
  return members;
}

// Each piece's triangles on the body. The followed folds cut the piece into regions that each
// lie in one plane of the body; a region's vertices on its border whose place the body tells
// (cone points, points of the folds it follows) give the rigid motion of its plane (least
// squares, Kabsch), and every other vertex of the region is moved by it. Every triangle is so
// an isometric copy of its flat one to rounding, and triangles on a fold share its points. Sets
// the rows of `out` not set yet that a region places; leaves the others: a region whose anchors
// lie in a line, or off its fitted plane by more than `misfitLimit` (mm).
void placeOnFaces(const Points2& flat, const std::vector<std::vector<int>>& regions,
                  const std::vector<std::optional<Eigen::Vector3d>>& known, double misfitLimit,
                  Points3& out) {
  const Eigen::Index nV = flat.rows();
  for (Eigen::Index v = 0; v < nV; ++v)
    if (known[std::size_t(v)]) out.row(v) = known[std::size_t(v)]->transpose();
  for (const std::vector<int>& vertices : regions) {
    std::vector<int> anchors;
    for (int v : vertices)
      if (known[std::size_t(v)]) anchors.push_back(v);
    if (anchors.size() < 3) continue;
    Eigen::Vector2d c2 = Eigen::Vector2d::Zero();
    Eigen::Vector3d c3 = Eigen::Vector3d::Zero();
    for (int v : anchors) {
      c2 += flat.row(v).transpose();
      c3 += *known[std::size_t(v)];
    }
    c2 /= double(anchors.size());
    c3 /= double(anchors.size());
    // Anchors in a line (a region whose other corners are flat seam points) leave its plane's
    // turn about that line open: the region waits for its seam points from the other piece.
    Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
    for (int v : anchors) spread += (flat.row(v).transpose() - c2) * (flat.row(v) - c2.transpose());
    const Eigen::Vector2d spreads =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread).eigenvalues();
    if (!(spreads[0] > kAnchorSpread * spreads[1])) continue;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (int v : anchors) {
      const Eigen::Vector2d p = flat.row(v).transpose() - c2;
      H += Eigen::Vector3d(p.x(), p.y(), 0.0) * (*known[std::size_t(v)] - c3).transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d R = svd.matrixV() * svd.matrixU().transpose();
    if (R.determinant() < 0) {
      Eigen::Matrix3d V = svd.matrixV();
      V.col(2) *= -1.0;
      R = V * svd.matrixU().transpose();
    }
    // Anchors off the fitted plane: the region is not one plane of the body. It spans a fold
    // gentler than kFollowedFold, which over a region 100 mm long puts its vertices up to 2e-4
    // mm off the body (seen on rounded squares of corner radii 40 and 8 at n = 1000, where
    // edges beside the seam of 1.3 mm came out 1.7e-4 longer than flat). Its vertices are traced
    // onto the body instead, where triangles across the fold are chords of it.
    double misfit = 0.0;
    for (int v : anchors) {
      const Eigen::Vector2d p = flat.row(v).transpose() - c2;
      misfit = std::max(
          misfit, (R * Eigen::Vector3d(p.x(), p.y(), 0.0) + c3 - *known[std::size_t(v)]).norm());
    }
    if (!(misfit <= misfitLimit)) continue;
    for (int v : vertices) {
      if (known[std::size_t(v)] || out.row(v).allFinite()) continue;
      const Eigen::Vector2d p = flat.row(v).transpose() - c2;
      out.row(v) = (R * Eigen::Vector3d(p.x(), p.y(), 0.0) + c3).transpose();
    }
  }
}

}  // namespace

bool placeBothOnFaces(const exact::ExactGluing& g, Piece* pieces[2],
                      std::vector<std::optional<Eigen::Vector3d>> known[2],
                      const std::vector<std::vector<int>> walls[2]) {
  std::vector<std::vector<int>> regions[2];
  double size[2];
  for (int p = 0; p < 2; ++p) {
    size[p] = (pieces[p]->flat.colwise().maxCoeff() - pieces[p]->flat.colwise().minCoeff()).norm();
    pieces[p]->shape =
        Points3::Constant(pieces[p]->flat.rows(), 3, std::numeric_limits<double>::quiet_NaN());
    regions[p] = regionsBetween(pieces[p]->F, walls[p]);
  }
  for (int pass = 0; pass < 3 && !(pieces[0]->shape.allFinite() && pieces[1]->shape.allFinite());
       ++pass)
    for (int p = 0; p < 2; ++p) {
      const Piece& other = *pieces[1 - p];
      for (std::size_t k = 0; k < pieces[p]->seam.size(); ++k) {
        std::optional<Eigen::Vector3d>& at = known[p][std::size_t(pieces[p]->seam[k])];
        if (!at && other.shape.row(other.seam[k]).allFinite())
          at = other.shape.row(other.seam[k]).transpose();
      }
      placeOnFaces(pieces[p]->flat, regions[p], known[p], kPlaneMisfit * size[p], pieces[p]->shape);
    }
  for (int p = 0; p < 2; ++p) {
    Piece& piece = *pieces[p];
    std::vector<Eigen::Index> missing;
    for (Eigen::Index v = 0; v < piece.flat.rows(); ++v)
      if (!piece.shape.row(v).allFinite()) missing.push_back(v);
    if (missing.empty()) continue;
    Points2 flat(Eigen::Index(missing.size()), 2);
    for (std::size_t i = 0; i < missing.size(); ++i)
      flat.row(Eigen::Index(i)) = piece.flat.row(missing[i]);
    const Points3 traced = exact::placeOnBody(g, p, flat);
    for (std::size_t i = 0; i < missing.size(); ++i)
      piece.shape.row(missing[i]) = traced.row(Eigen::Index(i));
    if (!piece.shape.allFinite()) return false;
  }
  return true;
}

double longestStretch(const Piece& piece) {
  double longest = 0.0;
  for (Eigen::Index f = 0; f < piece.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int i = piece.F(f, c), j = piece.F(f, (c + 1) % 3);
      const double flat = (piece.flat.row(i) - piece.flat.row(j)).norm();
      longest = std::max(longest, (piece.shape.row(i) - piece.shape.row(j)).norm() / flat - 1.0);
    }
  return longest;
}

}  // namespace dform
