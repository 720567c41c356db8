// SPDX-License-Identifier: GPL-3.0-or-later
// Every use of CGAL in dform: the constrained Delaunay triangulation behind triangulateDomain and
// the 3D convex hull. Exact predicates throughout; exact constructions for the hull only.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <new>
#include <string>
#include <utility>

#include "cgal_backend.h"
#include "dform/core/interrupt.h"
#include "dform/meshing/convex_hull.h"

namespace dform {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // input row
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;   // nesting level
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Any crossing of constraints, even through a vertex, throws: the caller's loops must be disjoint.
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;
// The 3D hull with exact constructions: quickhull's with inexact ones fails on curves that are
// planar but for rounding (an assertion with CGAL's checks on, out-of-bounds writes without),
// and the hull of a seam curve of 1000 points takes about 6 ms either way.
using HullKernel = CGAL::Exact_predicates_exact_constructions_kernel;

Status invalidDomain(std::string message) { return {ErrorCode::InputInvalid, std::move(message)}; }

// A failed allocation is not bad input nor a bug: the run needs more memory than it can get
// (the memory check before meshing could not foresee it), a usage matter like a resolution too
// large for the machine (README "Exit codes").
Status outOfMemory(const char* what) {
  return {ErrorCode::Usage, std::string("out of memory while ") + what + "; try a lower " +
                                mention(Setting::Resolution)};
}

// Level 0 is the unbounded region; crossing a loop's edge enters the next level (`isChainEdge`
// tells the constrained edges that do not bound a region).
template <typename IsChainEdge>
void markNestingLevels(Cdt& cdt, IsChainEdge isChainEdge) {
  for (auto f : cdt.all_face_handles()) f->info() = -1;
  std::vector<Cdt::Face_handle> seeds{cdt.infinite_face()};
  for (int level = 0; !seeds.empty(); ++level) {
    std::vector<Cdt::Face_handle> across;
    std::vector<Cdt::Face_handle> stack = std::move(seeds);
    while (!stack.empty()) {
      const Cdt::Face_handle f = stack.back();
      stack.pop_back();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle g = f->neighbor(i);
        if (g->info() != -1) continue;
        const bool bounds = f->is_constrained(i) && !isChainEdge(f->vertex(Cdt::cw(i))->info(),
                                                                 f->vertex(Cdt::ccw(i))->info());
        (bounds ? across : stack).push_back(g);
      }
    }
    seeds = std::move(across);
  }
}

}  // namespace

namespace meshing_detail {

Result<Faces> constrainedDelaunay(const Points2& P, const std::vector<Loop>& loops,
                                  const std::vector<std::vector<int>>& chains) {
  const int n = int(P.rows());
  std::vector<K::Point_2> points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) points.emplace_back(P(i, 0), P(i, 1));

  // CGAL's range insertion (spatially sorted, each point located from the last one's face),
  // written out so that a stop is polled while hundreds of thousands of points go in. The order,
  // and so the triangulation of cocircular lattice points, is the one the range insertion makes.
  std::vector<std::size_t> order(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using SortTraits =
      CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<K::Point_2>::type>;
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(points)));
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vertex(static_cast<std::size_t>(n));
  Cdt::Face_handle hint;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k % 4096 == 0) throwIfInterrupted("the meshing");
    const std::size_t i = order[k];
    const Cdt::Vertex_handle v = cdt.insert(points[i], hint);
    if (v == Cdt::Vertex_handle()) continue;
    v->info() = int(i);
    hint = v->face();
  }
  if (int(cdt.number_of_vertices()) != n) return invalidDomain("two points of the domain coincide");
  for (auto v : cdt.finite_vertex_handles()) vertex[std::size_t(v->info())] = v;

  std::vector<std::pair<int, int>> edges;  // every constraint, loops' first
  for (const Loop& loop : loops)
    for (int k = 0; k < loop.count; ++k)
      edges.emplace_back(loop.first + k, loop.first + (k + 1) % loop.count);
  const std::size_t loopEdges = edges.size();
  for (const std::vector<int>& chain : chains)
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) edges.emplace_back(chain[k], chain[k + 1]);
  std::vector<std::pair<int, int>> chainEdges;
  for (std::size_t e = loopEdges; e < edges.size(); ++e)
    chainEdges.emplace_back(std::min(edges[e].first, edges[e].second),
                            std::max(edges[e].first, edges[e].second));
  std::sort(chainEdges.begin(), chainEdges.end());

  const char* const kTouching =
      chains.empty() ? "the outline and holes cross or touch each other"
                     : "the outline, holes and crease lines cross or touch each other";
  try {
    for (const auto& [a, b] : edges) cdt.insert_constraint(vertex[a], vertex[b]);
  } catch (const std::bad_alloc&) {
    return outOfMemory("meshing");
  } catch (const std::exception&) {
    return invalidDomain(kTouching);
  }
  // The guarantee the solver relies on: no constraint edge was split, no vertex was added.
  if (int(cdt.number_of_vertices()) != n) return invalidDomain(kTouching);
  for (const auto& [a, b] : edges)
    if (!cdt.is_edge(vertex[a], vertex[b])) return invalidDomain(kTouching);

  markNestingLevels(cdt, [&](int a, int b) {
    return std::binary_search(chainEdges.begin(), chainEdges.end(),
                              std::make_pair(std::min(a, b), std::max(a, b)));
  });
  for (std::size_t e = loopEdges; e < edges.size(); ++e) {  // a chain runs inside the domain
    Cdt::Face_handle face;
    int i = 0;
    cdt.is_edge(vertex[edges[e].first], vertex[edges[e].second], face, i);
    if (face->info() % 2 == 0 || face->neighbor(i)->info() % 2 == 0)
      return invalidDomain("a crease line leaves the piece");
  }
  std::vector<std::array<int, 3>> inside;
  inside.reserve(cdt.number_of_faces());
  for (auto f : cdt.finite_face_handles())
    if (f->info() % 2 == 1)
      inside.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  Faces F(Eigen::Index(inside.size()), 3);
  for (std::size_t t = 0; t < inside.size(); ++t)
    for (int c = 0; c < 3; ++c) F(Eigen::Index(t), c) = inside[t][c];
  return F;
}

}  // namespace meshing_detail

Result<ConvexHull3> convexHull3(const Points3& P) {
  const Eigen::Index n = P.rows();
  if (!P.allFinite()) return invalidDomain("the curve has a non-finite coordinate");
  if (n < 4)
    return invalidDomain("the curve has fewer than 4 points: its convex hull has no inside");

  std::vector<HullKernel::Point_3> points;
  points.reserve(n);
  for (Eigen::Index i = 0; i < n; ++i) points.emplace_back(P(i, 0), P(i, 1), P(i, 2));

  // Exactly coplanar input would give CGAL's flat (2D) hull, which has no inside.
  Eigen::Index second = 1, third, fourth;
  while (second < n && points[second] == points[0]) ++second;
  for (third = second + 1; third < n; ++third)
    if (!CGAL::collinear(points[0], points[second], points[third])) break;
  for (fourth = third + 1; fourth < n; ++fourth)
    if (!CGAL::coplanar(points[0], points[second], points[third], points[fourth])) break;
  const Status planar = invalidDomain("the curve is planar: its convex hull has no inside");
  if (fourth >= n) return planar;

  std::vector<HullKernel::Point_3> hullPoints;
  std::vector<std::array<int, 3>> hullFaces;
  try {
    CGAL::convex_hull_3(points.begin(), points.end(), hullPoints, hullFaces);
  } catch (const std::bad_alloc&) {
    return outOfMemory("computing a convex hull");
  } catch (const std::exception& e) {  // CGAL precondition failures: a bug, not bad input
    return Status(ErrorCode::Internal, std::string("convex hull failed: ") + e.what());
  }

  // Hull vertices are copies of input points, so exact coordinates map them back.
  std::map<std::array<double, 3>, int> rowOf;
  for (Eigen::Index i = n - 1; i >= 0; --i) rowOf[{P(i, 0), P(i, 1), P(i, 2)}] = int(i);
  std::vector<int> inputRow(hullPoints.size());
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t h = 0; h < hullPoints.size(); ++h) {
    // Input coordinates are doubles, so the exact ones convert back without rounding.
    const Eigen::Vector3d p(CGAL::to_double(hullPoints[h].x()), CGAL::to_double(hullPoints[h].y()),
                            CGAL::to_double(hullPoints[h].z()));
    inputRow[h] = rowOf.at({p.x(), p.y(), p.z()});
    centre += p;
  }
  centre /= double(hullPoints.size());

  ConvexHull3 hull;
  hull.F.resize(Eigen::Index(hullFaces.size()), 3);
  double volume = 0.0, area = 0.0;
  const HullKernel::Point_3 inner(centre.x(), centre.y(), centre.z());
  for (std::size_t f = 0; f < hullFaces.size(); ++f) {
    std::array<int, 3> t = hullFaces[f];
    // Outward means the inner point is on the negative side; swap two corners if CGAL disagrees.
    if (CGAL::orientation(hullPoints[t[0]], hullPoints[t[1]], hullPoints[t[2]], inner) ==
        CGAL::POSITIVE)
      std::swap(t[1], t[2]);
    for (int c = 0; c < 3; ++c) hull.F(Eigen::Index(f), c) = inputRow[t[c]];
    const Eigen::Vector3d a = P.row(inputRow[t[0]]), b = P.row(inputRow[t[1]]),
                          c = P.row(inputRow[t[2]]);
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    area += 0.5 * normal.norm();
    volume += normal.dot(a - centre) / 6.0;
  }
  const double diagonal = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  // Rounding leaves a "planar" curve a sliver of relative thickness ~1e-16; real shapes are far
  // thicker than 1e-9 of their size.
  const double flatness = 1e-9 * diagonal;
  if (!(area > 0.0) || 2.0 * volume / area < flatness) return planar;

  std::vector<bool> isHullRow(std::size_t(n), false);
  for (int row : inputRow) isHullRow[std::size_t(row)] = true;
  hull.onHull.resize(std::size_t(n));
  hull.distanceToHull.assign(std::size_t(n), 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    hull.onHull[std::size_t(i)] = isHullRow[std::size_t(rowOf.at({P(i, 0), P(i, 1), P(i, 2)}))];
    if (hull.onHull[std::size_t(i)]) continue;
    // Inside a convex polytope the distance to the surface is the least distance to a face plane.
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < hull.F.rows(); ++f) {
      const Eigen::Vector3d a = P.row(hull.F(f, 0)), b = P.row(hull.F(f, 1)),
                            c = P.row(hull.F(f, 2));
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      const double length = normal.norm();
      if (length > 0.0)
        nearest = std::min(nearest, normal.dot(a - Eigen::Vector3d(P.row(i))) / length);
    }
    hull.distanceToHull[std::size_t(i)] = std::max(0.0, nearest);
  }
  return hull;
}

}  // namespace dform
