// SPDX-License-Identifier: GPL-3.0-or-later
#include "cgal_checks.h"

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_3.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/intersections.h>
#include <CGAL/property_map.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

#include "dform/core/interrupt.h"

namespace dform::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Segment = Kernel::Segment_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Point point(const Points3& V, int i) { return Point(V(i, 0), V(i, 1), V(i, 2)); }

// Whether triangles f and g, which share `shared` (1 or 2) vertex indices, overlap beyond them.
// Same rules as CGAL::Polygon_mesh_processing::does_self_intersect for adjacent faces.
bool adjacentOverlap(const Points3& V, const Faces& F, int f, int g) {
  std::array<int, 3> a{F(f, 0), F(f, 1), F(f, 2)}, b{F(g, 0), F(g, 1), F(g, 2)};
  std::vector<int> common;
  for (int i : a)
    if (std::find(b.begin(), b.end(), i) != b.end()) common.push_back(i);
  if (common.size() == 3) return true;  // the same triangle twice
  auto others = [&](const std::array<int, 3>& t) {
    std::vector<int> rest;
    for (int i : t)
      if (std::find(common.begin(), common.end(), i) == common.end()) rest.push_back(i);
    return rest;
  };
  const std::vector<int> ra = others(a), rb = others(b);
  if (common.size() == 2) {
    // Folded onto each other: coplanar with both free corners on the same side of the edge.
    const Point p = point(V, common[0]), q = point(V, common[1]);
    const Point r = point(V, ra[0]), s = point(V, rb[0]);
    return CGAL::coplanar(p, q, r, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
  }
  // One shared corner: they overlap beyond it exactly when the edge opposite it in one triangle
  // meets the other triangle.
  const Triangle ta(point(V, a[0]), point(V, a[1]), point(V, a[2]));
  const Triangle tb(point(V, b[0]), point(V, b[1]), point(V, b[2]));
  return CGAL::do_intersect(Segment(point(V, ra[0]), point(V, ra[1])), tb) ||
         CGAL::do_intersect(Segment(point(V, rb[0]), point(V, rb[1])), ta);
}

// Whether triangles f and g lie face to face: each one's corners within `tolerance` of the
// other's plane, their normals (from the faces' corner order) pointing opposite ways. Near-
// coplanar pairs have normals near parallel or antiparallel, so the sign of the dot product is
// far from rounding whenever the distances pass.
bool faceToFace(const Points3& V, const Faces& F, int f, int g, double tolerance) {
  auto corner = [&](int t, int k) -> Eigen::Vector3d { return V.row(F(t, k)).transpose(); };
  auto normal = [&](int t) {
    return (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).normalized();
  };
  const Eigen::Vector3d nf = normal(f), ng = normal(g);
  if (!(nf.dot(ng) < 0.0)) return false;
  auto withinPlaneOf = [&](int t, const Eigen::Vector3d& n, int other) {
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(n.dot(corner(other, k) - corner(t, 0))) <= tolerance)) return false;
    return true;
  };
  return withinPlaneOf(f, nf, g) && withinPlaneOf(g, ng, f);
}

}  // namespace

SelfIntersections findSelfIntersections(const Points3& V, const Faces& F) {
  SelfIntersections result;
  std::vector<bool> used(size_t(V.rows()), false);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[size_t(F(f, k))] = true;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (used[size_t(i)]) {
      low = low.cwiseMin(V.row(i).transpose());
      high = high.cwiseMax(V.row(i).transpose());
    }
  const double contactTolerance = F.rows() > 0 ? kFaceToFaceTolerance * (high - low).norm() : 0.0;
  std::vector<Box> boxes;
  boxes.reserve(size_t(F.rows()));
  for (int f = 0; f < F.rows(); ++f) {
    if (f % kPollInterval == 0) throwIfInterrupted("the figures");
    const Point p = point(V, F(f, 0)), q = point(V, F(f, 1)), r = point(V, F(f, 2));
    if (CGAL::collinear(p, q, r)) {  // no plane: the degenerate-triangle check reports it
      ++result.skippedDegenerate;
      continue;
    }
    boxes.emplace_back(p.bbox() + q.bbox() + r.bbox(), f);
  }
  long candidates = 0;
  auto report = [&](const Box& x, const Box& y) {
    if (++candidates % kPollInterval == 0) throwIfInterrupted("the figures");
    const int f = std::min(x.info(), y.info()), g = std::max(x.info(), y.info());
    if (faceToFace(V, F, f, g, contactTolerance)) {
      ++result.faceToFace;
      return;
    }
    bool shares = false;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) shares = shares || F(f, i) == F(g, j);
    const bool hit =
        shares
            ? adjacentOverlap(V, F, f, g)
            : CGAL::do_intersect(Triangle(point(V, F(f, 0)), point(V, F(f, 1)), point(V, F(f, 2))),
                                 Triangle(point(V, F(g, 0)), point(V, F(g, 1)), point(V, F(g, 2))));
    if (!hit) return;
    if (result.pairs == 0)
      result.example = "triangles " + std::to_string(f) + " and " + std::to_string(g);
    ++result.pairs;
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), report);
  return result;
}

// The hull is read off a triangulation of the points (the facets of its infinite cells), not
// made by convex_hull_3: CGAL 5.5's quickhull can leave a visible region whose border is no single
// loop where many points lie on hull faces (the seam of a body with flat sides, points of both
// pieces on them), and then reads past the end of its border map; which inputs do so follows the
// memory addresses of its vertices, so one run crashed and the next did not. The triangulation's
// predicates are exact and its result does not depend on the order of the points.
std::optional<HullMesh> convexHull(const Points3& P) {
  std::vector<Point> points;
  points.reserve(size_t(P.rows()));
  for (int i = 0; i < P.rows(); ++i) points.push_back(point(P, i));
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 4) return std::nullopt;
  using Triangulation = CGAL::Triangulation_3<Kernel>;
  const Triangulation t(points.begin(), points.end());
  // Coplanar or collinear points span no solid.
  if (t.dimension() < 3) return std::nullopt;
  std::map<Triangulation::Vertex_handle, int> index;
  std::vector<Eigen::Vector3i> faces;
  std::vector<Eigen::Vector3d> corners;
  std::vector<Triangulation::Cell_handle> cells;
  t.incident_cells(t.infinite_vertex(), std::back_inserter(cells));
  for (const Triangulation::Cell_handle& cell : cells) {
    const int infinite = cell->index(t.infinite_vertex());
    // The facet opposite the infinite vertex, turned so that the finite cell behind it (its
    // vertex off the facet, inside the hull) lies on the side its normal points away from.
    Triangulation::Vertex_handle v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = cell->vertex(Triangulation::vertex_triple_index(infinite, k));
    const Triangulation::Cell_handle behind = cell->neighbor(infinite);
    const Point& inner = behind->vertex(behind->index(cell))->point();
    if (CGAL::orientation(v[0]->point(), v[1]->point(), v[2]->point(), inner) == CGAL::POSITIVE)
      std::swap(v[1], v[2]);
    Eigen::Vector3i face;
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = index.emplace(v[k], int(corners.size()));
      if (added) corners.emplace_back(v[k]->point().x(), v[k]->point().y(), v[k]->point().z());
      face[k] = it->second;
    }
    faces.push_back(face);
  }
  if (faces.size() != 2 * corners.size() - 4) return std::nullopt;
  HullMesh hull;
  hull.V.resize(Eigen::Index(corners.size()), 3);
  for (size_t i = 0; i < corners.size(); ++i) hull.V.row(Eigen::Index(i)) = corners[i].transpose();
  hull.F.resize(Eigen::Index(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) hull.F.row(Eigen::Index(i)) = faces[i].transpose();
  return hull;
}

std::vector<int> convexHull2(const Points2& P) {
  std::vector<Kernel::Point_2> points;
  points.reserve(size_t(P.rows()));
  for (int i = 0; i < P.rows(); ++i) points.emplace_back(P(i, 0), P(i, 1));
  std::vector<std::size_t> indices(points.size()), corners;
  std::iota(indices.begin(), indices.end(), std::size_t(0));
  using Traits =
      CGAL::Convex_hull_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  CGAL::convex_hull_2(indices.begin(), indices.end(), std::back_inserter(corners),
                      Traits(CGAL::make_property_map(points)));
  return std::vector<int>(corners.begin(), corners.end());
}

}  // namespace dform::detail
