// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/validate/gate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <utility>

#include "cgal_checks.h"
#include "dform/core/interrupt.h"
#include "dform/core/piece_loops.h"
#include "dform/core/polyline.h"
#include "mesh_measures.h"

namespace dform {

namespace {

using Verdict = CheckResult::Verdict;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// Max |angle defect| over both pieces' vertices that neither lie on the boundary, the seam or a
// crease nor share an edge with one: the paper's "zero Gaussian curvature everywhere except the
// seam", and the issue's "away from seam and creases".
CheckResult gaussCheck(const DForm& model, const GateLimits& limits) {
  const bool creased = isVariant(model.a) || isVariant(model.b);
  double worst = 0.0;
  int counted = 0;
  std::string where;
  for (const Piece* p : {&model.a, &model.b}) {
    const std::vector<bool> away = detail::awayFromSeam(*p, detail::edgeTopology(p->F));
    const Eigen::VectorXd defect = detail::angleDefects(p->shape, p->F);
    for (Eigen::Index v = 0; v < defect.size(); ++v) {
      if (!away[v]) continue;
      ++counted;
      if (std::abs(defect(v)) > worst || where.empty()) {
        worst = std::max(worst, std::abs(defect(v)));
        where = "piece " + p->name + " vertex " + std::to_string(v);
      }
    }
  }
  if (counted == 0)
    return notRunCheck("gauss_max_rad", limits.gaussMaxRad,
                       "no interior vertex away from the seam" +
                           std::string(creased ? ", the boundary and the creases" : ""));
  return judgeCheck("gauss_max_rad", worst, limits.gaussMaxRad,
                    "largest |angle defect| over " + std::to_string(counted) +
                        " vertices away from the seam" +
                        (creased ? ", the boundary and the creases" : "") + ", at " + where);
}

// What is wrong with a piece's flat boundary loops (empty when nothing): a loop that crosses or
// touches itself, two loops that meet, a hole outside the outer outline or inside another hole.
std::string loopProblems(const Piece& p) {
  const std::vector<std::vector<int>> loops = boundaryLoops(p);
  std::vector<Points2> points;
  for (const auto& loop : loops) points.push_back(loopPoints(p.flat, loop));
  // A classic piece keeps the old wording: its seam is its outline.
  auto name = [&](size_t k) {
    if (k == 0) return std::string(loops.size() == 1 ? "outline" : "seam loop");
    return "free boundary " + std::to_string(k);
  };
  std::string problem;
  auto add = [&](const std::string& what) { problem += (problem.empty() ? "" : "; ") + what; };
  for (size_t k = 0; k < loops.size(); ++k)
    if (const auto cross = findSelfIntersection(points[k]))
      add(name(k) + " edges " + std::to_string(cross->first) + " and " +
          std::to_string(cross->second) + " meet");
  for (size_t k = 0; k < loops.size(); ++k)
    for (size_t l = k + 1; l < loops.size(); ++l)
      if (const auto meet = findCrossing(points[k], points[l]))
        add(name(k) + " edge " + std::to_string(meet->first) + " and " + name(l) + " edge " +
            std::to_string(meet->second) + " meet");
  if (!problem.empty()) return problem;  // nesting is only defined for loops that do not meet
  const size_t outer = size_t(outerLoopIndex(p));
  for (size_t k = 0; k < loops.size(); ++k) {
    if (k == outer) continue;
    const Eigen::Vector2d q = points[k].row(0).transpose();
    if (!insidePolygon(points[outer], q)) add(name(k) + " lies outside the outer outline");
    for (size_t l = 0; l < loops.size(); ++l)
      if (l != k && l != outer && insidePolygon(points[l], q))
        add(name(k) + " lies inside " + name(l));
  }
  return problem;
}

CheckResult flatSimpleCheck(const DForm& model) {
  int bad = 0;
  std::string detail;
  for (const Piece* p : {&model.a, &model.b}) {
    if (p->seam.size() < 3)
      return notRunCheck("flat_simple", 0, "piece " + p->name + " has no seam outline");
    std::string problem = loopProblems(*p);
    std::string example;
    if (const int overlaps = detail::countFlatOverlaps(p->flat, p->F, &example); overlaps > 0)
      problem += (problem.empty() ? "" : "; ") + std::to_string(overlaps) +
                 " overlapping triangle pairs (" + example + ")";
    if (problem.empty()) continue;
    ++bad;
    detail += (detail.empty() ? "" : "; ") + ("piece " + p->name + ": " + problem);
  }
  if (bad == 0)
    detail = isVariant(model.a) || isVariant(model.b)
                 ? "both flat pieces are simple (holes inside their outer outline, no loops "
                   "meeting) and no two flat triangles overlap"
                 : "both flat pieces are simple and no two flat triangles overlap";
  return judgeCheck("flat_simple", bad, 0, detail);
}

// The first coordinate of the model that is not a finite number, "piece A's 3D vertex 0" (empty
// when none). CGAL's exact predicates cannot take one (its multiprecision fallback asserts), so
// the checks that need them fail on such a model instead of calling CGAL.
std::string nonFiniteCoordinate(const DForm& model) {
  auto firstBad = [](const auto& points) {
    for (Eigen::Index v = 0; v < points.rows(); ++v)
      if (!points.row(v).allFinite()) return v;
    return Eigen::Index(-1);
  };
  for (const Piece* p : {&model.a, &model.b}) {
    if (const Eigen::Index v = firstBad(p->shape); v >= 0)
      return "piece " + p->name + "'s 3D vertex " + std::to_string(v);
    if (const Eigen::Index v = firstBad(p->flat); v >= 0)
      return "piece " + p->name + "'s flat vertex " + std::to_string(v);
  }
  return {};
}

CheckResult nonFiniteCheck(const char* name, double limit, const std::string& where) {
  return judgeCheck(name, kNaN, limit,
                    "not measured: " + where + " has a coordinate that is not a number");
}

// Reverses the faces from row `firstOfB` on when most welded edges they share with the faces
// before it run the same way in both, so that the soup is oriented consistently: the test for
// sheets lying face to face compares the faces' normals.
void orientLikeFirstPiece(Faces& F, int firstOfB) {
  std::set<std::pair<int, int>> edgesOfA;
  for (int f = 0; f < firstOfB; ++f)
    for (int k = 0; k < 3; ++k) edgesOfA.emplace(F(f, k), F(f, (k + 1) % 3));
  int same = 0, opposite = 0;
  for (int f = firstOfB; f < int(F.rows()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = F(f, k), v = F(f, (k + 1) % 3);
      same += int(edgesOfA.count({u, v}));
      opposite += int(edgesOfA.count({v, u}));
    }
  if (same <= opposite) return;
  for (int f = firstOfB; f < int(F.rows()); ++f) std::swap(F(f, 1), F(f, 2));
}

// Both pieces as one triangle soup, each seam pair welded into one vertex at its midpoint (the
// gap itself is judged by seam_gap_mm), so that triangles meeting at the seam are adjacent.
CheckResult selfIntersectionCheck(const DForm& model) {
  if (const std::string where = nonFiniteCoordinate(model); !where.empty())
    return nonFiniteCheck("self_intersection", 0, where);
  const Piece& a = model.a;
  const Piece& b = model.b;
  const int na = int(a.shape.rows());
  Points3 V(na + b.shape.rows(), 3);
  V << a.shape, b.shape;
  std::vector<int> weld(size_t(V.rows()));
  for (int i = 0; i < int(V.rows()); ++i) weld[i] = i;
  for (size_t i = 0; i < a.seam.size(); ++i) {
    weld[na + b.seam[i]] = a.seam[i];
    V.row(a.seam[i]) = 0.5 * (a.shape.row(a.seam[i]) + b.shape.row(b.seam[i]));
  }
  Faces F(a.F.rows() + b.F.rows(), 3);
  F << a.F, (b.F.array() + na).unaryExpr([&](int i) { return weld[i]; }).matrix();
  orientLikeFirstPiece(F, int(a.F.rows()));
  const detail::SelfIntersections hits = detail::findSelfIntersections(V, F);
  std::string text = hits.pairs == 0 ? "no two triangles of the closed surface intersect"
                                     : std::to_string(hits.pairs) +
                                           " intersecting triangle pairs, first " + hits.example;
  if (hits.faceToFace > 0)
    text += "; " + std::to_string(hits.faceToFace) +
            " nearby pairs lie face to face, facing opposite ways (sheets touching, not crossing)";
  if (hits.skippedDegenerate > 0)
    text += " (" + std::to_string(hits.skippedDegenerate) + " degenerate triangles not tested)";
  return judgeCheck("self_intersection", hits.pairs, 0, text);
}

// How far the solve may leave a seam corner from where it was drawn, as a fraction of the seam's
// length: ForwardSettings::outlineTolerance, the tolerance its constraint rounds meet (validate
// reads meshes only and does not depend on forward).
constexpr double kSeamCornerSlack = 3e-4;

struct Convexity {
  double pocketMm = 0;  ///< the deepest pocket: a vertex's distance from the hull edge spanning it
  double toleranceMm = 0;  ///< the deepest pocket sampling and solving can make on a convex outline
};

// How far the closed flat seam S (simple, either orientation) departs from convex, and how far it
// may. A convex drawn outline reaches the solved flat seam moved by at most
//   delta = max(kSeamCornerSlack * L, max_i kappa_i h_i^2 / 24)     (L the seam's length):
// a corner and its two seam neighbours are held only to within kSeamCornerSlack * L of where they
// were drawn; every other seam vertex is held exactly at its sample, which compensateChordLoss
// moved off the drawn curve by kappa h^2 / 24 (kappa the curvature of the circle through it and
// its neighbours, h its mean edge length), the move measured here by applying it to S. So every
// vertex lies within delta of a convex curve, the hull of the vertices within delta of that curve
// (hulls are 1-Lipschitz in the Hausdorff distance), and a vertex within 2 delta of the hull edge
// spanning it. A deeper pocket was drawn so. The hull's corners come in S's order along S, since S
// is simple, so each run of other vertices lies between the two corners of one hull edge.
Convexity flatConvexity(const Points2& S) {
  Convexity c;
  const int n = int(S.rows());
  const Eigen::VectorXd chordLossMoves = (compensateChordLoss(S) - S).rowwise().norm();
  c.toleranceMm = 2.0 * std::max(kSeamCornerSlack * closedLength(S), chordLossMoves.maxCoeff());
  const std::vector<int> corners = detail::convexHull2(S);
  if (corners.size() < 3) {  // collinear: no inside, nothing is convex
    c.pocketMm = std::numeric_limits<double>::infinity();
    return c;
  }
  std::vector<bool> isCorner(size_t(n), false);
  for (int k : corners) isCorner[size_t(k)] = true;
  int last = corners.front();
  for (int step = 1; step <= n; ++step) {
    const int i = (corners.front() + step) % n;
    if (!isCorner[size_t(i)]) continue;
    for (int j = (last + 1) % n; j != i; j = (j + 1) % n)
      c.pocketMm = std::max(c.pocketMm, distanceToSegment(S.row(j), S.row(last), S.row(i)));
    last = i;
  }
  return c;
}

// Distance from p to triangle (a, b, c) (closest point by Voronoi regions, Ericson 5.1.5).
double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

struct HullDistance {
  double worstMm = 0;     ///< the largest distance from a 3D vertex to the hull's surface
  double diagonalMm = 0;  ///< the diagonal of the seam points' bounding box
  std::string where;      ///< the vertex, "piece A vertex 12"
};

// The largest distance from a 3D vertex of either piece to the surface of the convex hull of the
// seam points (both sides); nullopt when the seam is planar (its hull has no inside).
std::optional<HullDistance> distanceToSeamHull(const DForm& model) {
  const size_t n = model.a.seam.size();
  Points3 seam(Eigen::Index(2 * n), 3);
  for (size_t i = 0; i < n; ++i) {
    seam.row(Eigen::Index(i)) = model.a.shape.row(model.a.seam[i]);
    seam.row(Eigen::Index(n + i)) = model.b.shape.row(model.b.seam[i]);
  }
  const std::optional<detail::HullMesh> hull = detail::convexHull(seam);
  if (!hull) return std::nullopt;
  HullDistance result;
  result.diagonalMm = (seam.colwise().maxCoeff() - seam.colwise().minCoeff()).norm();
  // Where seam points are coplanar, CGAL's quickhull triangulates their facet in an order that
  // follows memory addresses (its border map is keyed by vertex handles), so a vertex on the hull
  // measures ~1e-13 of the diagonal, a different rounding each run. Below this floor, about 5e4
  // units in the last place of the diagonal, a vertex is on the hull: 0, the same every run.
  const double onHullMm = 1e-11 * result.diagonalMm;
  // Inside a convex hull the nearest surface point lies on the nearest face's plane (the ball that
  // reaches that plane lies inside every face's half-space), so a vertex inside takes the smallest
  // plane distance; one outside (or on the surface, by rounding) is measured face by face. Faces
  // of no area (collinear seam points) carry no surface and are left out of the planes.
  const Eigen::Index faces = hull->F.rows();
  Eigen::Matrix<double, 4, Eigen::Dynamic> planes(4, faces);  // unit outward normal, offset
  Eigen::Index planeCount = 0;
  for (Eigen::Index h = 0; h < faces; ++h) {
    const Eigen::Vector3d a = hull->V.row(hull->F(h, 0)), b = hull->V.row(hull->F(h, 1)),
                          c = hull->V.row(hull->F(h, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    if (!(normal.norm() > 1e-12 * result.diagonalMm * result.diagonalMm)) continue;
    const Eigen::Vector3d unit = normal.normalized();
    planes.col(planeCount) << unit, -unit.dot(a);
    ++planeCount;
  }
  planes.conservativeResize(4, planeCount);
  for (const Piece* p : {&model.a, &model.b})
    for (int v = 0; v < p->shape.rows(); ++v) {
      if (v % kPollInterval == 0) throwIfInterrupted("the figures");
      const Eigen::Vector4d q(p->shape(v, 0), p->shape(v, 1), p->shape(v, 2), 1.0);
      double d = -(planes.transpose() * q).maxCoeff();  // the nearest plane, when inside them all
      if (!(d > 0.0)) {
        d = std::numeric_limits<double>::infinity();
        for (Eigen::Index h = 0; h < faces; ++h)
          d = std::min(
              d, pointTriangleDistance(p->shape.row(v), hull->V.row(hull->F(h, 0)),
                                       hull->V.row(hull->F(h, 1)), hull->V.row(hull->F(h, 2))));
      }
      if (d < onHullMm) d = 0.0;
      if (d > result.worstMm || result.where.empty()) {
        result.worstMm = std::max(result.worstMm, d);
        result.where = "piece " + p->name + " vertex " + std::to_string(v);
      }
    }
  return result;
}

// The seam pairs where a corner of one flat seam meets a point where the other was drawn smooth,
// as "piece B's corners at seam pairs 12, 37 meet smooth points of piece A" (empty when none).
// There the 3D seam kinks where one piece's outline is smooth, which a developable sheet can do
// only by folding: the real D-Form creases from that point into the smooth piece (paper section
// 7 and Fig. 14a, the Squaricle) and is its seam's hull with those creases as edges, while a model
// without creases bends over them (Fig. 14b) and cannot be the hull. Corners meeting corners force
// no crease (each sheet kinks at its own corner): those are judged.
std::string cornersMeetingSmoothPoints(const DForm& model) {
  const std::vector<bool> corner[2] = {sampledCorners(loopPoints(model.a.flat, model.a.seam)),
                                       sampledCorners(loopPoints(model.b.flat, model.b.seam))};
  const Piece* pieces[2] = {&model.a, &model.b};
  std::string text;
  for (int p = 0; p < 2; ++p) {
    std::string pairs;
    for (size_t i = 0; i < corner[p].size(); ++i)
      if (corner[p][i] && !corner[1 - p][i])
        pairs += (pairs.empty() ? "" : ", ") + std::to_string(i);
    if (!pairs.empty())
      text += (text.empty() ? "" : "; ") +
              ("piece " + pieces[p]->name + "'s corners at seam pairs " + pairs +
               " meet smooth points of piece " + pieces[1 - p]->name);
  }
  return text;
}

// Demaine & Price: a D-Form of two convex pieces is the convex hull of its seam. Measures the
// largest distance from a 3D vertex to the hull surface of the seam points (both sides).
CheckResult hullCheck(const DForm& model, const GateLimits& limits) {
  const char* name = "hull_distance_rel";
  if (const std::string where = nonFiniteCoordinate(model); !where.empty())
    return nonFiniteCheck(name, limits.hullDistanceRel, where);
  std::string convexity;
  for (const Piece* p : {&model.a, &model.b}) {
    if (!p->freeBoundaries.empty())
      return notRunCheck(name, limits.hullDistanceRel,
                         "piece " + p->name +
                             " has a free boundary (an anti or demi D-Form): the convex-hull "
                             "property holds for two convex discs zipped along their outlines");
    if (!p->creases.empty())
      return notRunCheck(name, limits.hullDistanceRel,
                         "piece " + p->name +
                             " has creases: the convex-hull property holds for crease-free "
                             "convex pieces only");
    if (p->seam.size() < 3)
      return notRunCheck(name, limits.hullDistanceRel,
                         "piece " + p->name + " has fewer than 3 seam vertices");
    const Points2 seam = loopPoints(p->flat, p->seam);
    if (findSelfIntersection(seam))
      return notRunCheck(name, limits.hullDistanceRel,
                         "piece " + p->name + " is not convex: its flat seam is not simple");
    const Convexity c = flatConvexity(seam);
    if (c.pocketMm > c.toleranceMm)
      return notRunCheck(name, limits.hullDistanceRel,
                         "piece " + p->name + " is not convex: its flat seam has a pocket " +
                             num(c.pocketMm) + " mm deep, more than the " + num(c.toleranceMm) +
                             " mm a convex outline may gain from its sampling and from the "
                             "solve's tolerance at corners");
    convexity += (convexity.empty() ? "" : ", ") + num(c.pocketMm) + " mm (" + p->name + ")";
  }
  const std::optional<HullDistance> d = distanceToSeamHull(model);
  if (!d)
    return notRunCheck(name, limits.hullDistanceRel, "the seam is planar: its hull has no inside");
  const std::string measured = "largest distance to the seam's convex hull " + num(d->worstMm) +
                               " mm (" + num(d->worstMm / d->diagonalMm) + " of the seam's " +
                               num(d->diagonalMm) + " mm bounding-box diagonal) at " + d->where;
  if (const std::string unmatched = cornersMeetingSmoothPoints(model); !unmatched.empty())
    return notRunCheck(name, limits.hullDistanceRel,
                       unmatched +
                           ": the real D-Form creases from there and is its seam's hull with "
                           "those creases as edges; this model has none and bends instead, so it "
                           "cannot be the hull (" +
                           measured + "); draw the creases to model them");
  return judgeCheck(name, d->worstMm / d->diagonalMm, limits.hullDistanceRel,
                    measured + "; both pieces convex (deepest flat-seam pocket " + convexity + ")");
}

}  // namespace

CheckResult judgeCheck(std::string name, double value, double limit, std::string detail) {
  const Verdict v = value <= limit ? Verdict::Pass : Verdict::Fail;
  return {std::move(name), value, limit, v, std::move(detail)};
}

CheckResult notRunCheck(std::string name, double limit, std::string reason) {
  return {std::move(name), kNaN, limit, Verdict::NotRun, std::move(reason)};
}

const char* verdictName(CheckResult::Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: return "pass";
    case Verdict::Fail: return "fail";
    case Verdict::NotRun: return "not run";
  }
  return "?";
}

bool GateReport::passed() const { return failed() == 0; }

int GateReport::failed() const {
  return int(std::count_if(checks.begin(), checks.end(),
                           [](const CheckResult& c) { return c.verdict == Verdict::Fail; }));
}

int GateReport::notRun() const {
  return int(std::count_if(checks.begin(), checks.end(),
                           [](const CheckResult& c) { return c.verdict == Verdict::NotRun; }));
}

const CheckResult* GateReport::find(const std::string& name) const {
  for (const CheckResult& c : checks)
    if (c.name == name) return &c;
  return nullptr;
}

namespace {

// A figure of the object a user builds (the exact D-Form of the pieces), or why it has none.
CheckResult objectCheck(const char* name, double rms, double max, double limit,
                        const std::string& note, const std::string& what) {
  if (std::isnan(rms)) return notRunCheck(name, limit, "no exact D-Form to compare with: " + note);
  return judgeCheck(name, rms, limit, what + " / the bounding-box diagonal; largest " + num(max));
}

}  // namespace

GateReport runGate(const DForm& model, const GateLimits& limits, const Metrics& metrics,
                   const Curve3* target, const CurveMatch* curve) {
  GateReport report;
  report.name = limits.name;
  report.limits = limits;
  const Metrics& m = report.metrics = metrics;
  auto& checks = report.checks;
  const size_t pairs = model.a.seam.size();

  checks.push_back(judgeCheck("L_error", m.lengthError, limits.lengthError,
                              "relative edge-length error over both pieces"));
  checks.push_back(judgeCheck("L_max", m.lengthErrorMax, limits.lengthErrorMax,
                              "largest relative error of one edge"));
  if (target) {
    if (size_t(target->points.rows()) != pairs || pairs == 0 || !curve) {
      checks.push_back(notRunCheck("D_error", limits.curveError,
                                   "the target curve has " + std::to_string(target->points.rows()) +
                                       " points for " + std::to_string(pairs) + " seam pairs"));
    } else {
      report.curve = *curve;
      checks.push_back(judgeCheck("D_error", report.curve->curveError, limits.curveError,
                                  "mean seam-to-curve distance / curve length; largest distance " +
                                      num(report.curve->curveDistanceMaxMm) + " mm"));
    }
  } else if (pairs == 0) {
    checks.push_back(notRunCheck("B_error", limits.seamError, "the model has no seam pairs"));
  } else {
    checks.push_back(judgeCheck("B_error", m.seamError, limits.seamError,
                                "mean seam-partner distance / 3D seam length"));
  }
  if (pairs == 0)
    checks.push_back(notRunCheck("seam_gap_mm", limits.seamGapMm, "the model has no seam pairs"));
  else
    checks.push_back(judgeCheck("seam_gap_mm", m.seamGapMm, limits.seamGapMm,
                                "largest seam-partner distance (mm)"));
  checks.push_back(gaussCheck(model, limits));
  checks.push_back(judgeCheck("flipped", m.flipped2d + m.flipped3d, limits.flipped,
                              std::to_string(m.flipped2d) + " flipped flat, " +
                                  std::to_string(m.flipped3d) + " folded-over 3D triangles"));
  checks.push_back(judgeCheck("degenerate", m.degenerate2d + m.degenerate3d, limits.degenerate,
                              std::to_string(m.degenerate2d) + " flat, " +
                                  std::to_string(m.degenerate3d) + " 3D degenerate triangles"));
  checks.push_back(flatSimpleCheck(model));
  const double longer = std::max(m.seamLengthAMm, m.seamLengthBMm);
  if (longer <= 0.0)
    checks.push_back(
        notRunCheck("seam_length_rel", limits.seamLengthRel, "the flat seams have no length"));
  else
    checks.push_back(judgeCheck(
        "seam_length_rel", std::abs(m.seamLengthAMm - m.seamLengthBMm) / longer,
        limits.seamLengthRel,
        "flat seams " + num(m.seamLengthAMm) + " mm and " + num(m.seamLengthBMm) + " mm"));
  checks.push_back(selfIntersectionCheck(model));
  checks.push_back(hullCheck(model, limits));
  checks.push_back(objectCheck(
      "exact_distance_rel", m.exactDistanceRmsRel, m.exactDistanceMaxRel, limits.exactDistanceRel,
      m.exactNote, "RMS distance of the 3D seam from the exact D-Form of these flat pieces"));
  if (report.curve)
    checks.push_back(objectCheck("roundtrip_rel", report.curve->roundtripRmsRel,
                                 report.curve->roundtripMaxRel, limits.roundtripRel,
                                 report.curve->roundtripNote,
                                 "RMS distance from the target curve of the pieces zipped again (" +
                                     report.curve->roundtripNote + ")"));
  return report;
}

}  // namespace dform
