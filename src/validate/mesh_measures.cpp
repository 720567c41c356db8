// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_measures.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

#include "dform/core/constants.h"
#include "dform/core/interrupt.h"

namespace dform::detail {
namespace {

// A triangle is degenerate when an angle is below this (radians): about 0.06 degrees, far below
// any angle a mesher or solver produces on purpose, large enough to catch slivers before they
// break normals and angle sums.
constexpr double kMinAngle = 1e-3;
// ... or when its area is below this fraction of the squared mean edge length: 1e-12 is ~1e4
// times the relative round-off of an area computed in double precision.
constexpr double kMinAreaFactor = 1e-12;

Eigen::Vector3d row3(const Points3& V, int i) { return V.row(i).transpose(); }

}  // namespace

EdgeTopology edgeTopology(const Faces& F) {
  // (min * 2^32 + max, face) per half-edge: sorted as the triples (min, max, face) would be, as
  // two machine words instead of three compared one by one.
  std::vector<std::pair<std::uint64_t, int>> halfEdges;
  halfEdges.reserve(size_t(F.rows()) * 3);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k), j = F(f, (k + 1) % 3);
      halfEdges.emplace_back(
          (std::uint64_t(std::uint32_t(std::min(i, j))) << 32) | std::uint32_t(std::max(i, j)), f);
    }
  throwIfInterrupted("the figures");
  std::sort(halfEdges.begin(), halfEdges.end());
  throwIfInterrupted("the figures");
  EdgeTopology t;
  for (size_t h = 0; h < halfEdges.size();) {
    const auto [key, f] = halfEdges[h];
    size_t next = h + 1;
    while (next < halfEdges.size() && halfEdges[next].first == key) ++next;
    t.edges.push_back({int(key >> 32), int(key & 0xFFFFFFFFu)});
    t.faces.push_back({f, next - h >= 2 ? halfEdges[h + 1].second : -1});
    h = next;
  }
  return t;
}

int edgeIndex(const EdgeTopology& topology, int i, int j) {
  const std::array<int, 2> key{std::min(i, j), std::max(i, j)};
  const auto it = std::lower_bound(topology.edges.begin(), topology.edges.end(), key);
  return it != topology.edges.end() && *it == key ? int(it - topology.edges.begin()) : -1;
}

std::vector<bool> boundaryOrCreaseVertices(const Piece& piece, const EdgeTopology& topology) {
  std::vector<bool> marked(size_t(piece.shape.rows()), false);
  for (size_t e = 0; e < topology.edges.size(); ++e)
    if (topology.faces[e][1] < 0)
      marked[topology.edges[e][0]] = marked[topology.edges[e][1]] = true;
  for (int v : piece.seam) marked[v] = true;
  for (const std::vector<int>& crease : piece.creases)
    for (int v : crease) marked[v] = true;
  return marked;
}

std::vector<bool> awayFromSeam(const Piece& piece, const EdgeTopology& topology) {
  const std::vector<bool> onBoundary = boundaryOrCreaseVertices(piece, topology);
  std::vector<bool> nearSeam = onBoundary;
  for (const auto& e : topology.edges)
    if (onBoundary[e[0]] || onBoundary[e[1]]) nearSeam[e[0]] = nearSeam[e[1]] = true;
  std::vector<bool> away(nearSeam.size(), false);
  for (int f = 0; f < piece.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) away[piece.F(f, k)] = !nearSeam[piece.F(f, k)];
  return away;
}

std::vector<bool> creaseEdges(const Piece& piece, const EdgeTopology& topology) {
  std::vector<bool> onCrease(topology.edges.size(), false);
  for (const std::vector<int>& crease : piece.creases)
    for (size_t k = 0; k + 1 < crease.size(); ++k)
      if (const int e = edgeIndex(topology, crease[k], crease[k + 1]); e >= 0) onCrease[e] = true;
  return onCrease;
}

double cornerAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - a, w = c - a;
  if (u.squaredNorm() == 0.0 || w.squaredNorm() == 0.0) return 0.0;
  return std::atan2(u.cross(w).norm(), u.dot(w));  // accurate for small and near-pi angles
}

Eigen::VectorXd angleDefects(const Points3& V, const Faces& F) {
  Eigen::VectorXd defect = Eigen::VectorXd::Constant(V.rows(), 2.0 * kPi);
  for (int f = 0; f < F.rows(); ++f) {
    if (f % kPollInterval == 0) throwIfInterrupted("the figures");
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3), c = F(f, (k + 2) % 3);
      defect(a) -= cornerAngle(row3(V, a), row3(V, b), row3(V, c));
    }
  }
  return defect;
}

Points3 lift(const Points2& P) {
  Points3 Q = Points3::Zero(P.rows(), 3);
  Q.leftCols<2>() = P;
  return Q;
}

bool isFlippedFlat(const Points2& P, const Faces& F, int f) {
  const Eigen::Vector2d a = P.row(F(f, 0)), b = P.row(F(f, 1)), c = P.row(F(f, 2));
  const Eigen::Vector2d u = b - a, w = c - a;
  return u.x() * w.y() - u.y() * w.x() <= 0.0;
}

int countDegenerate(const Points3& V, const Faces& F, const EdgeTopology& topology) {
  double meanEdge = 0.0;
  for (const auto& e : topology.edges) meanEdge += (V.row(e[0]) - V.row(e[1])).norm();
  if (!topology.edges.empty()) meanEdge /= double(topology.edges.size());
  const double minArea = kMinAreaFactor * meanEdge * meanEdge;
  int count = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = row3(V, F(f, 0)), b = row3(V, F(f, 1)), c = row3(V, F(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double smallest =
        std::min({cornerAngle(a, b, c), cornerAngle(b, c, a), cornerAngle(c, a, b)});
    if (smallest < kMinAngle || area < minArea || !std::isfinite(area)) ++count;
  }
  return count;
}

// A 3D triangle is "folded back over" when, across an interior edge whose two flat triangles are
// both counter-clockwise (the flat layout there is unfolded: dihedral 0), the unit normals of the
// two 3D triangles have a negative dot product, i.e. the surface turns by more than 90 degrees
// between neighbouring triangles. A smooth developable surface meshed at any reasonable density
// never does; a solver that folds a sheet onto itself does. Each triangle counts once, however many
// of its edges are folded. A crease (a hinge edge) may fold by any angle: the designer drew it.
int countFolded(const Points2& flat, const Points3& shape, const Faces& F,
                const EdgeTopology& topology, const std::vector<bool>& hinge) {
  std::vector<Eigen::Vector3d> normal(size_t(F.rows()));
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = row3(shape, F(f, 0)), b = row3(shape, F(f, 1)),
                          c = row3(shape, F(f, 2));
    normal[f] = (b - a).cross(c - a);
  }
  std::vector<bool> folded(size_t(F.rows()), false);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const auto [f, g] = topology.faces[e];
    if (g < 0 || hinge[e] || isFlippedFlat(flat, F, f) || isFlippedFlat(flat, F, g)) continue;
    if (normal[f].dot(normal[g]) < 0.0) folded[f] = folded[g] = true;
  }
  return int(std::count(folded.begin(), folded.end(), true));
}

int countFlatOverlaps(const Points2& P, const Faces& F, std::string* example) {
  const int n = int(F.rows());
  if (n == 0) return 0;
  std::vector<Eigen::Vector2d> lo(static_cast<size_t>(n)), hi(static_cast<size_t>(n));
  double meanEdge = 0.0;
  for (int f = 0; f < n; ++f) {
    lo[f] = hi[f] = P.row(F(f, 0)).transpose();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d p = P.row(F(f, k));
      lo[f] = lo[f].cwiseMin(p);
      hi[f] = hi[f].cwiseMax(p);
      meanEdge += (P.row(F(f, k)) - P.row(F(f, (k + 1) % 3))).norm();
    }
  }
  meanEdge /= 3.0 * n;
  // Interiors must overlap by more than this (mm) to count: neighbours sharing an edge meet with
  // a gap of a few ulps of the coordinates; 1e-9 of an edge is ~1e7 ulps and far below any overlap
  // that matters for cutting.
  const double tol = 1e-9 * meanEdge;

  // Separating-axis test on the 6 edge normals: two triangles overlap when no axis separates
  // their projections by more than -tol.
  auto overlap = [&](int f, int g) {
    for (int t = 0; t < 2; ++t) {
      const int h = t == 0 ? f : g;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d d = P.row(F(h, (k + 1) % 3)) - P.row(F(h, k));
        const double len = d.norm();
        if (len == 0.0) continue;
        const Eigen::Vector2d axis(-d.y() / len, d.x() / len);
        double min1 = INFINITY, max1 = -INFINITY, min2 = INFINITY, max2 = -INFINITY;
        for (int j = 0; j < 3; ++j) {
          const double s1 = axis.dot(P.row(F(f, j)).transpose());
          const double s2 = axis.dot(P.row(F(g, j)).transpose());
          min1 = std::min(min1, s1), max1 = std::max(max1, s1);
          min2 = std::min(min2, s2), max2 = std::max(max2, s2);
        }
        if (std::max(min2 - max1, min1 - max2) >= -tol) return false;
      }
    }
    return true;
  };

  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo[a].x() < lo[b].x(); });
  int count = 0;
  for (int oi = 0; oi < n; ++oi) {
    if (oi % kPollInterval == 0) throwIfInterrupted("the figures");
    const int f = order[oi];
    for (int oj = oi + 1; oj < n && lo[order[oj]].x() < hi[f].x(); ++oj) {
      const int g = order[oj];
      if (lo[g].y() >= hi[f].y() || lo[f].y() >= hi[g].y()) continue;
      if (!overlap(f, g)) continue;
      if (count == 0 && example)
        *example = "triangles " + std::to_string(std::min(f, g)) + " and " +
                   std::to_string(std::max(f, g));
      ++count;
    }
  }
  return count;
}

double seamLength(const Eigen::Ref<const Eigen::MatrixXd>& V, const std::vector<int>& idx) {
  double length = 0.0;
  const size_t n = idx.size();
  for (size_t i = 0; i < n; ++i) length += (V.row(idx[(i + 1) % n]) - V.row(idx[i])).norm();
  return length;
}

}  // namespace dform::detail
