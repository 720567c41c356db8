// SPDX-License-Identifier: GPL-3.0-or-later
// Meshing a flat domain with its boundary kept exactly: interior points come from a hexagonal
// lattice kept clear of the boundary, a constrained Delaunay triangulation joins them to the fixed
// boundary points, and a few rounds of interior-only smoothing and re-triangulation even out the
// triangles. Refinement never touches a boundary edge, so both pieces of a D-Form keep the same
// boundary vertices one to one (CGAL's Delaunay_mesher_2 would split encroached boundary edges).
#include "dform/meshing/triangulate.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "cgal_backend.h"
#include "dform/core/interrupt.h"
#include "dform/core/polyline.h"

namespace dform {
namespace {

using meshing_detail::Loop;

// A lattice point closer than this many target lengths to the boundary is dropped: the first
// interior row then sits about one triangle height (0.87 h) from the boundary, and no triangle
// between the boundary and the lattice gets an edge much shorter than h.
constexpr double kClearance = 0.6;
// Smoothing rounds: the mesh settles in a handful; each round costs one triangulation.
constexpr int kMaxSmoothingRounds = 8;
// Rounds stop once no interior point moves farther than this fraction of h.
constexpr double kSettledMove = 0.02;
// Above this many interior points the target length is surely a unit mistake.
constexpr double kMaxInteriorPoints = 2e7;

Status invalid(std::string message) { return {ErrorCode::InputInvalid, std::move(message)}; }

Status checkLoop(const Points2& P, const std::string& name) {
  if (P.rows() < 3) return invalid(name + " has fewer than 3 points");
  if (!P.allFinite()) return invalid(name + " has a non-finite coordinate");
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (P.row(i) == P.row((i + 1) % P.rows()))
      return invalid(name + " repeats point " + std::to_string(i));
  if (const auto crossing = findSelfIntersection(P))
    return invalid(name + " crosses itself at edges " + std::to_string(crossing->first) + " and " +
                   std::to_string(crossing->second));
  if (signedArea(P) == 0.0) return invalid(name + " encloses no area");
  return Status::ok();
}

// Constraint edges bucketed in square cells of side h, so that "is q within r <= 0.6 h of an
// edge" looks at the 3 by 3 cells around q only.
class EdgeGrid {
 public:
  EdgeGrid(const Points2& P, const std::vector<std::pair<int, int>>& edges, double h)
      : P_(P), h_(h) {
    lo_ = P.colwise().minCoeff().transpose();
    nx_ = int(std::floor((P.col(0).maxCoeff() - lo_.x()) / h)) + 1;
    ny_ = int(std::floor((P.col(1).maxCoeff() - lo_.y()) / h)) + 1;
    cells_.resize(std::size_t(nx_) * ny_);
    for (const auto& [a, b] : edges) {
      edges_.push_back({a, b});
      // Samples h/2 apart lie within h/4 of every point of the edge: with r <= 0.6 h, an edge
      // near q has a sample within 0.85 h, so in one of the 3 by 3 cells around q.
      const Eigen::Vector2d pa = P.row(a), pb = P.row(b);
      const int steps = int(std::ceil((pb - pa).norm() / (0.5 * h))) + 1;
      for (int s = 0; s <= steps; ++s) {
        std::vector<int>& cell = cells_[index(pa + (pb - pa) * (double(s) / steps))];
        if (cell.empty() || cell.back() != int(edges_.size()) - 1)
          cell.push_back(int(edges_.size()) - 1);
      }
    }
  }

  bool near(const Eigen::Vector2d& q, double r) const {
    assert(r <= kClearance * h_ && "EdgeGrid looks at the neighbouring cells only");
    const int cx = cellX(q), cy = cellY(q);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, ny_ - 1); ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, nx_ - 1); ++x)
        for (int e : cells_[std::size_t(y) * nx_ + x])
          if (distanceToSegment(q, P_.row(edges_[e].first), P_.row(edges_[e].second)) < r)
            return true;
    return false;
  }

 private:
  int cellX(const Eigen::Vector2d& q) const {
    return std::clamp(int(std::floor((q.x() - lo_.x()) / h_)), 0, nx_ - 1);
  }
  int cellY(const Eigen::Vector2d& q) const {
    return std::clamp(int(std::floor((q.y() - lo_.y()) / h_)), 0, ny_ - 1);
  }
  std::size_t index(const Eigen::Vector2d& q) const {
    return std::size_t(cellY(q)) * nx_ + cellX(q);
  }

  const Points2& P_;
  double h_;
  Eigen::Vector2d lo_;
  int nx_ = 0, ny_ = 0;
  std::vector<std::pair<int, int>> edges_;
  std::vector<std::vector<int>> cells_;
};

// Points of a hexagonal lattice of spacing h inside the domain (even-odd over all loops) and at
// least kClearance * h from every constraint edge (loops' and interior lines').
std::vector<Eigen::Vector2d> latticePoints(const Points2& P, const std::vector<Loop>& loops,
                                           const std::vector<std::pair<int, int>>& constraintEdges,
                                           double h) {
  const double rowStep = h * std::sqrt(3.0) / 2.0;
  const double x0 = P.col(0).minCoeff(), y0 = P.col(1).minCoeff();
  const int rows = int(std::floor((P.col(1).maxCoeff() - y0) / rowStep)) + 1;
  // Scanlines: where each row crosses the loops, found edge by edge.
  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(rows));
  auto rowY = [&](int j) { return y0 + (j + 0.5) * rowStep; };
  for (const Loop& loop : loops)
    for (int k = 0; k < loop.count; ++k) {
      const Eigen::Vector2d a = P.row(loop.first + k);
      const Eigen::Vector2d b = P.row(loop.first + (k + 1) % loop.count);
      const int jLo = std::max(0, int(std::floor((std::min(a.y(), b.y()) - y0) / rowStep - 0.5)));
      const int jHi = std::min(rows - 1, int(std::ceil((std::max(a.y(), b.y()) - y0) / rowStep)));
      for (int j = jLo; j <= jHi; ++j) {
        const double y = rowY(j);
        if ((a.y() > y) != (b.y() > y))  // half-open, so a vertex on the row counts once
          crossings[std::size_t(j)].push_back(a.x() +
                                              (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
      }
    }
  const EdgeGrid grid(P, constraintEdges, h);
  std::vector<Eigen::Vector2d> points;
  for (int j = 0; j < rows; ++j) {
    std::vector<double>& xs = crossings[std::size_t(j)];
    std::sort(xs.begin(), xs.end());
    const double shift = (j % 2) * 0.5;
    for (std::size_t s = 0; s + 1 < xs.size(); s += 2) {
      const int iLo = int(std::ceil((xs[s] - x0) / h - shift));
      const int iHi = int(std::floor((xs[s + 1] - x0) / h - shift));
      for (int i = iLo; i <= iHi; ++i) {
        const Eigen::Vector2d q(x0 + (i + shift) * h, rowY(j));
        if (q.x() > xs[s] && q.x() < xs[s + 1] && !grid.near(q, kClearance * h))
          points.push_back(q);
      }
    }
  }
  return points;
}

double twiceArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

Eigen::Vector2d circumcentre(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a;
  const double d = 2.0 * (u.x() * v.y() - u.y() * v.x());
  return a + Eigen::Vector2d(v.y() * u.squaredNorm() - u.y() * v.squaredNorm(),
                             u.x() * v.squaredNorm() - v.x() * u.squaredNorm()) /
                 d;
}

// One Gauss-Seidel sweep moving each free vertex (index >= fixedCount) to its optimal-Delaunay
// position (area-weighted mean of the circumcentres around it), or else to the centroid of its
// star. A move is taken only if every triangle around the vertex stays clearly counter-clockwise,
// so points stay strictly inside their star and thus inside the domain, off every boundary edge.
// Returns the largest move.
double smoothInterior(Points2& V, const Faces& F, int fixedCount) {
  const int n = int(V.rows());
  std::vector<int> start(std::size_t(n) + 1, 0), around(std::size_t(F.size()));
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int c = 0; c < 3; ++c) ++start[std::size_t(F(t, c)) + 1];
  for (int v = 0; v < n; ++v) start[std::size_t(v) + 1] += start[std::size_t(v)];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    for (int c = 0; c < 3; ++c) around[std::size_t(fill[std::size_t(F(t, c))]++)] = int(t);

  double largestMove = 0.0;
  for (int v = fixedCount; v < n; ++v) {
    // The star's outer edge (a, b) of each triangle (v, a, b), in counter-clockwise order.
    std::vector<std::pair<int, int>> link;
    for (int k = start[std::size_t(v)]; k < start[std::size_t(v) + 1]; ++k) {
      const int t = around[std::size_t(k)];
      const int c = F(t, 0) == v ? 0 : F(t, 1) == v ? 1 : 2;
      link.emplace_back(F(t, (c + 1) % 3), F(t, (c + 2) % 3));
    }
    const Eigen::Vector2d old = V.row(v);
    double area = 0.0;
    Eigen::Vector2d odt = Eigen::Vector2d::Zero(), centroid = Eigen::Vector2d::Zero();
    for (const auto& [a, b] : link) {
      const Eigen::Vector2d pa = V.row(a), pb = V.row(b);
      const double w = twiceArea(old, pa, pb);
      area += w;
      odt += w * circumcentre(old, pa, pb);
      centroid += w * (old + pa + pb) / 3.0;
    }
    if (!(area > 0.0)) continue;
    // Clearly counter-clockwise: each triangle keeps at least 1% of the star's mean area.
    const double minArea = 0.01 * area / double(link.size());
    for (const Eigen::Vector2d& target :
         {Eigen::Vector2d(odt / area), Eigen::Vector2d(centroid / area)}) {
      if (!target.allFinite()) continue;
      const bool valid = std::all_of(link.begin(), link.end(), [&](const std::pair<int, int>& e) {
        return twiceArea(target, V.row(e.first), V.row(e.second)) > minArea;
      });
      if (!valid) continue;
      largestMove = std::max(largestMove, (target - old).norm());
      V.row(v) = target;
      break;
    }
  }
  return largestMove;
}

// Smallest angle (degrees) of the triangles with no fixed vertex: the ones smoothing can improve.
double minInteriorAngle(const Points2& V, const Faces& F, int fixedCount) {
  const double pi = std::acos(-1.0);
  double smallest = pi;  // radians
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    if (F.row(t).minCoeff() < fixedCount) continue;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d p = V.row(F(t, c)), u = V.row(F(t, (c + 1) % 3)) - p.transpose(),
                            v = V.row(F(t, (c + 2) % 3)) - p.transpose();
      smallest = std::min(smallest, std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v)));
    }
  }
  return smallest * 180.0 / pi;
}

}  // namespace

Result<FlatMesh> triangulateDomain(const Points2& boundary, const std::vector<Points2>& holes,
                                   const TriangulateOptions& options,
                                   const std::vector<InteriorLine>& lines) {
  const double h = options.targetEdgeLength;
  if (!std::isfinite(h) || h <= 0.0)
    return Status(ErrorCode::Usage, "the target edge length must be positive");
  if (!std::isfinite(options.minAngleDegrees) || options.minAngleDegrees < 0.0 ||
      options.minAngleDegrees >= 60.0)
    return Status(ErrorCode::Usage, "the minimum angle must be in [0, 60) degrees");

  if (Status s = checkLoop(boundary, "the outline"); !s.isOk()) return s;
  if (signedArea(boundary) < 0.0) return invalid("the outline is clockwise, not counter-clockwise");
  double area = signedArea(boundary);
  for (std::size_t k = 0; k < holes.size(); ++k) {
    const std::string name = "hole " + std::to_string(k);
    if (Status s = checkLoop(holes[k], name); !s.isOk()) return s;
    // Crossings are found by the triangulation; here only whole loops in the wrong place.
    if (!insidePolygon(boundary, holes[k].row(0).transpose()))
      return invalid(name + " is not wholly inside the outline");
    for (std::size_t other = 0; other < holes.size(); ++other)
      if (other != k && insidePolygon(holes[other], holes[k].row(0).transpose()))
        return invalid(name + " overlaps hole " + std::to_string(other));
    area -= std::abs(signedArea(holes[k]));
  }
  if (area / (h * h) > kMaxInteriorPoints)
    return invalid("the target edge length is too small for the domain (over " +
                   std::to_string(long(kMaxInteriorPoints)) + " points)");

  // Fixed points first, in the order the contract promises: outline, each hole, each line.
  std::vector<Loop> loops{{0, int(boundary.rows())}};
  int fixedCount = int(boundary.rows());
  for (const Points2& hole : holes) {
    loops.push_back({fixedCount, int(hole.rows())});
    fixedCount += int(hole.rows());
  }
  const int loopPoints = fixedCount;
  std::vector<std::pair<int, int>> constraintEdges;
  for (const Loop& loop : loops)
    for (int k = 0; k < loop.count; ++k)
      constraintEdges.emplace_back(loop.first + k, loop.first + (k + 1) % loop.count);
  std::vector<std::vector<int>> chains;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const InteriorLine& line = lines[k];
    if (line.from < 0 || line.from >= loopPoints || line.to < 0 || line.to >= loopPoints ||
        line.interior.cols() != 2 || !line.interior.allFinite() ||
        (line.from == line.to && line.interior.rows() == 0))
      return invalid("crease line " + std::to_string(k) + " does not join two boundary points");
    std::vector<int> chain{line.from};
    for (Eigen::Index i = 0; i < line.interior.rows(); ++i) chain.push_back(fixedCount++);
    chain.push_back(line.to);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i)
      constraintEdges.emplace_back(chain[i], chain[i + 1]);
    chains.push_back(std::move(chain));
  }
  Points2 fixed(fixedCount, 2);
  fixed.topRows(boundary.rows()) = boundary;
  for (std::size_t k = 0; k < holes.size(); ++k)
    fixed.middleRows(loops[k + 1].first, holes[k].rows()) = holes[k];
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (lines[k].interior.rows() > 0)
      fixed.middleRows(chains[k][1], lines[k].interior.rows()) = lines[k].interior;

  const std::vector<Eigen::Vector2d> interior = latticePoints(fixed, loops, constraintEdges, h);
  FlatMesh mesh;
  mesh.V.resize(fixedCount + Eigen::Index(interior.size()), 2);
  mesh.V.topRows(fixedCount) = fixed;
  for (std::size_t i = 0; i < interior.size(); ++i)
    mesh.V.row(fixedCount + Eigen::Index(i)) = interior[i];

  try {
    Result<Faces> faces = meshing_detail::constrainedDelaunay(mesh.V, loops, chains);
    if (!faces.isOk()) return faces.status();
    for (int round = 0; round < kMaxSmoothingRounds && mesh.V.rows() > fixedCount; ++round) {
      const double moved = smoothInterior(mesh.V, faces.value(), fixedCount);
      faces = meshing_detail::constrainedDelaunay(mesh.V, loops, chains);
      // Smoothing keeps points strictly inside the domain, so this cannot fail.
      assert(faces.isOk() && "smoothing moved a point onto the boundary");
      if (!faces.isOk()) return Status(ErrorCode::Internal, faces.status().message());
      if (moved < kSettledMove * h &&
          minInteriorAngle(mesh.V, faces.value(), fixedCount) >= options.minAngleDegrees)
        break;
    }
    mesh.F = std::move(faces.value());
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  }
  mesh.boundary.resize(std::size_t(boundary.rows()));
  for (Eigen::Index i = 0; i < boundary.rows(); ++i) mesh.boundary[std::size_t(i)] = int(i);
  mesh.lines = std::move(chains);
  return mesh;
}

Result<Faces> triangulateBoundaryPoints(const Points2& points,
                                        const std::vector<std::pair<int, int>>& loops,
                                        const std::vector<std::pair<int, int>>& edges) {
  std::vector<Loop> cdtLoops;
  for (const auto& [first, count] : loops) cdtLoops.push_back({first, count});
  std::vector<std::vector<int>> chains;
  for (const auto& [a, b] : edges) chains.push_back({a, b});
  try {
    return meshing_detail::constrainedDelaunay(points, cdtLoops, chains);
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  }
}

}  // namespace dform
