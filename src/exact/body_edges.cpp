// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/exact/body_edges.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dform/core/pattern_ldlt.h"
#include "plane_angles.h"

namespace dform::exact {

namespace {

using plane::ccwAngle;
using plane::cross;

Eigen::Vector2d rotated(const Eigen::Vector2d& u, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * u.x() - s * u.y(), s * u.x() + c * u.y()};
}

// Walks the geodesics of the glued surface through the flat pieces.
class Walker {
 public:
  explicit Walker(const ExactGluing& g) : g_(g), n_(int(g.seam.a.rows())) {}

  int wrap(int k) const { return ((k % n_) + n_) % n_; }
  const Points2& side(int piece) const { return piece == 0 ? g_.seam.a : g_.seam.b; }
  Eigen::Vector2d point(int piece, int k) const { return side(piece).row(wrap(k)).transpose(); }
  double cone(int k) const { return g_.angles.a[k] + g_.angles.b[k]; }
  double chordLength(int k) const {
    return 0.5 * ((point(0, k + 1) - point(0, k)).norm() + (point(1, k + 1) - point(1, k)).norm());
  }

  // The signpost angle at seam point k of the direction u in piece `piece`'s plane.
  double signpostOf(int piece, int k, const Eigen::Vector2d& u) const {
    if (piece == 0) {
      const double phi = ccwAngle(point(0, k + 1) - point(0, k), u);
      return phi > g_.angles.a[k] + 0.5 * (2.0 * kPi - g_.angles.a[k]) ? 0.0 : phi;
    }
    const double phi = ccwAngle(point(1, k - 1) - point(1, k), u);
    return g_.angles.a[k] + (phi > g_.angles.b[k] + 0.5 * (2.0 * kPi - g_.angles.b[k]) ? 0.0 : phi);
  }

  // Maps a direction crossing chord k out of `piece` into the other piece's plane: the rigid
  // motion that glues the chord's two sides.
  Eigen::Vector2d across(int piece, int k, const Eigen::Vector2d& d) const {
    const Eigen::Vector2d from = (point(piece, k + 1) - point(piece, k)).normalized();
    const Eigen::Vector2d to = (point(1 - piece, k + 1) - point(1 - piece, k)).normalized();
    const Eigen::Vector2d local(d.dot(from), cross(from, d));
    return local.x() * to + local.y() * Eigen::Vector2d(-to.y(), to.x());
  }

  struct Hit {
    double lambda = std::numeric_limits<double>::infinity();
    int chord = -1;
    double mu = 0;
  };

  // The first chord of `piece` that the ray x + lambda d (lambda > 0) meets, leaving out the
  // chords `skip1`, `skip2` that hold x.
  Hit cast(int piece, const Eigen::Vector2d& x, const Eigen::Vector2d& d, int skip1, int skip2,
           double scale) const {
    Hit best;
    for (int c = 0; c < n_; ++c) {
      if (c == skip1 || c == skip2) continue;
      const Eigen::Vector2d p0 = point(piece, c), e = point(piece, c + 1) - p0;
      const double denom = cross(d, e);
      if (std::abs(denom) <= 1e-15 * e.norm()) continue;  // parallel
      const Eigen::Vector2d w = p0 - x;
      const double lambda = cross(w, e) / denom, mu = cross(w, d) / denom;
      if (lambda <= 1e-12 * scale || mu < -1e-9 || mu > 1.0 + 1e-9) continue;
      if (lambda < best.lambda) best = {lambda, c, std::clamp(mu, 0.0, 1.0)};
    }
    return best;
  }

  Status trace(int halfedge, double snap, BodyEdge& edge) const;
  void straighten(BodyEdge& edge) const;

 private:
  const ExactGluing& g_;
  int n_;
};

Status Walker::trace(int h, double snap, BodyEdge& edge) const {
  const IntrinsicTriangulation& T = g_.triangulation;
  const int target = edge.to;
  const double length = T.length(h);
  // An edge's length and signpost come from flips (the law of cosines, chained), which round to
  // ~1e-7 of it across a flat face triangulated many times over, and the walk ends up to ~1e-6
  // of it beside its far end (circle + square at n = 452: 1.1e-6); the edge is found from its
  // ends, which are seam points a chord apart (over 1e-3 of any edge), so the tolerance only
  // tells them apart. straighten() then draws it from its ends to rounding.
  const double lengthTolerance = 1e-5 * length;
  auto fail = [&](const std::string& why) {
    return Status(ErrorCode::SolveFailed, "the body's edge from seam point " +
                                              std::to_string(edge.from) + " to " +
                                              std::to_string(target) + " " + why);
  };
  // The walk: at a seam point with a signpost, or inside a piece at a place on the seam with a
  // flat direction. Each step either follows a seam chord or crosses a piece.
  int vertex = edge.from;
  double sigma = T.signpost(h);
  double walked = 0.0;
  int piece = 0;
  SeamPlace place{edge.from, 0.0};
  Eigen::Vector2d x, d;
  bool atVertex = true;
  const double angularTolerance = 1e-9;
  for (int step = 0; step < 4 * n_ + 8; ++step) {
    if (atVertex) {
      const double alphaA = g_.angles.a[vertex];
      sigma = std::fmod(sigma, cone(vertex));
      if (sigma < 0) sigma += cone(vertex);
      // Along a seam chord: from the start of A's wedge (to k + 1), its end (to k - 1, where B's
      // wedge starts), or the end of B's (to k + 1 again).
      int along = 0;
      if (sigma <= angularTolerance || sigma >= cone(vertex) - angularTolerance)
        along = +1;
      else if (std::abs(sigma - alphaA) <= angularTolerance)
        along = -1;
      if (along != 0) {
        const int next = wrap(vertex + along);
        walked += chordLength(along > 0 ? vertex : next);
        if (std::abs(walked - length) <= lengthTolerance) {
          if (next != target) return fail("ends at seam point " + std::to_string(next));
          edge.length = walked;
          return Status::ok();
        }
        if (walked > length || g_.vertexOfSeam[next] >= 0)
          return fail("runs along the seam into a cone point");
        // Straight on through the flat point: half its cone angle past the way back.
        const double back = along > 0 ? g_.angles.a[next] : 0.0;
        sigma = back + 0.5 * cone(next);
        vertex = next;
        continue;
      }
      piece = sigma <= alphaA ? 0 : 1;
      const Eigen::Vector2d base = piece == 0 ? point(0, vertex + 1) - point(0, vertex)
                                              : point(1, vertex - 1) - point(1, vertex);
      d = rotated(base.normalized(), piece == 0 ? sigma : sigma - alphaA);
      x = point(piece, vertex);
      place = {vertex, 0.0};
    }
    const int skip1 = place.isSeamPoint() ? wrap(place.chord - 1) : place.chord;
    const Hit hit = cast(piece, x, d, skip1, place.chord, length);
    const double remaining = length - walked;
    // The far end: the ray reaches its seam point as the length runs out, with no chord before.
    // (A ray aimed at a seam point may pass its two chords' ends by rounding, so the end is
    // judged by where the length runs out, not by the chord hit.)
    const bool reachesTarget = (x + remaining * d - point(piece, target)).norm() <= lengthTolerance;
    if (reachesTarget && !(hit.lambda < remaining - lengthTolerance)) {
      edge.runs.push_back({piece, place, {target, 0.0}});
      return Status::ok();
    }
    if (hit.chord < 0) return fail("leaves its piece");
    if (hit.lambda > remaining)
      return fail("ends inside a piece, " +
                  std::to_string((x + remaining * d - point(piece, target)).norm()) +
                  " mm from it");
    SeamPlace reached{hit.chord, hit.mu};
    if (hit.mu <= snap)
      reached = {hit.chord, 0.0};
    else if (hit.mu >= 1.0 - snap)
      reached = {wrap(hit.chord + 1), 0.0};
    edge.runs.push_back({piece, place, reached});
    walked += hit.lambda;
    if (reached.isSeamPoint()) {
      // Through a seam point: only a flat one (no vertex of the body) lets a geodesic pass.
      const int w = reached.chord;
      if (g_.vertexOfSeam[w] >= 0)
        return fail("meets seam point " + std::to_string(w) + ", a cone point, on its way");
      sigma = signpostOf(piece, w, -d) + 0.5 * cone(w);
      vertex = w;
      atVertex = true;
      continue;
    }
    // Across the seam into the other piece, at the same place of the glued chord.
    d = across(piece, hit.chord, d).normalized();
    piece = 1 - piece;
    x = point(piece, hit.chord) + hit.mu * (point(piece, hit.chord + 1) - point(piece, hit.chord));
    place = reached;
    atVertex = false;
  }
  return fail("does not end");
}

// The edge drawn straight in the plane of its first run: each later run's piece is laid into that
// plane by the rigid motions that glue the chords it crossed (at a flat seam point passed, the
// chord beside it: both glue alike there). Its length is then the distance from its first seam
// point to its last one laid so, and each place where it meets the seam the point of that chord
// the straight line crosses: both to rounding of the pieces' coordinates, where the walk that
// found the edge followed a direction and a length that flips left off by up to ~1e-7.
void Walker::straighten(BodyEdge& edge) const {
  if (edge.runs.empty()) return;
  // Row r: the rigid motion x -> R x + t from the plane of run r into the plane of run 0.
  std::vector<Eigen::Matrix2d> R(edge.runs.size(), Eigen::Matrix2d::Identity());
  std::vector<Eigen::Vector2d> t(edge.runs.size(), Eigen::Vector2d::Zero());
  for (std::size_t r = 1; r < edge.runs.size(); ++r) {
    const EdgeRun& before = edge.runs[r - 1];
    const EdgeRun& run = edge.runs[r];
    R[r] = R[r - 1];
    t[r] = t[r - 1];
    if (run.piece == before.piece) continue;
    const int k = run.from.chord;
    const Eigen::Vector2d from0 = point(run.piece, k), from1 = point(run.piece, k + 1);
    const Eigen::Vector2d to0 = point(before.piece, k), to1 = point(before.piece, k + 1);
    const Eigen::Vector2d u = (from1 - from0).normalized(), w = (to1 - to0).normalized();
    Eigen::Matrix2d rot;
    rot << u.dot(w), -cross(u, w), cross(u, w), u.dot(w);
    // Each side's chord glued at its middle: the two are equally long to rounding.
    const Eigen::Vector2d shift = 0.5 * (to0 + to1) - rot * (0.5 * (from0 + from1));
    t[r] = R[r - 1] * shift + t[r - 1];
    R[r] = R[r - 1] * rot;
  }
  const Eigen::Vector2d start = point(edge.runs.front().piece, edge.from);
  const Eigen::Vector2d end = R.back() * point(edge.runs.back().piece, edge.to) + t.back();
  const Eigen::Vector2d d = end - start;
  edge.length = d.norm();
  edge.runs.back().toLength = edge.length;
  for (std::size_t r = 1; r < edge.runs.size(); ++r) {
    SeamPlace& place = edge.runs[r].from;
    const int piece = edge.runs[r].piece;
    if (place.isSeamPoint()) {
      const double along = (R[r] * point(piece, place.chord) + t[r] - start).norm();
      edge.runs[r].fromLength = edge.runs[r - 1].toLength = along;
      continue;
    }
    const Eigen::Vector2d p0 = R[r] * point(piece, place.chord) + t[r],
                          p1 = R[r] * point(piece, place.chord + 1) + t[r];
    // A line along the chord (parallel to rounding) keeps the place the walk found.
    const double denom = cross(d, p1 - p0);
    if (std::abs(denom) > 1e-15 * d.norm() * (p1 - p0).norm())
      place.t = std::clamp(cross(start - p0, d) / -denom, std::nextafter(0.0, 1.0),
                           std::nextafter(1.0, 0.0));
    edge.runs[r - 1].to = place;
    edge.runs[r].fromLength = edge.runs[r - 1].toLength = (p0 + place.t * (p1 - p0) - start).norm();
  }
}

}  // namespace

Eigen::Vector2d seamPlacePoint(const ExactGluing& g, int piece, const SeamPlace& place) {
  const Points2& P = piece == 0 ? g.seam.a : g.seam.b;
  const long n = P.rows();
  const Eigen::Vector2d p0 = P.row(place.chord).transpose(),
                        p1 = P.row((place.chord + 1) % n).transpose();
  return place.isSeamPoint() ? p0 : Eigen::Vector2d(p0 + place.t * (p1 - p0));
}

namespace {

double foldOf(const ExactGluing& g, int h) {
  const IntrinsicTriangulation& T = g.triangulation;
  auto normal = [&](int f) {
    const Eigen::Vector3d p0 = g.vertices.row(T.tail(3 * f)),
                          p1 = g.vertices.row(T.tail(3 * f + 1)),
                          p2 = g.vertices.row(T.tail(3 * f + 2));
    return Eigen::Vector3d((p1 - p0).cross(p2 - p0).normalized());
  };
  const Eigen::Vector3d n1 = normal(h / 3), n2 = normal(T.twin(h) / 3);
  return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
}

}  // namespace

double fitBodyToEdges(ExactGluing& g, std::vector<BodyEdge>& edges) {
  if (g.doublyCovered || edges.empty()) return 0.0;
  const Eigen::Index unknowns = 3 * g.vertices.rows();
  const Eigen::MatrixX3d start = g.vertices;
  double residual = 0.0;
  // The normal matrix's pattern is the edges' at every iteration: ordered once.
  PatternLDLT ldlt;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(36 * edges.size() + std::size_t(unknowns));
  for (int iteration = 0; iteration < 4; ++iteration) {
    entries.clear();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
    residual = 0.0;
    for (const BodyEdge& edge : edges) {
      const int i = g.vertexOfSeam[std::size_t(edge.from)],
                j = g.vertexOfSeam[std::size_t(edge.to)];
      const Eigen::Vector3d e = g.vertices.row(i) - g.vertices.row(j);
      const double r = e.norm() - edge.length;
      residual = std::max(residual, std::abs(r) / edge.length);
      const Eigen::Vector3d u = e / e.norm();
      for (int a = 0; a < 3; ++a) {
        rhs[3 * i + a] -= r * u[a];
        rhs[3 * j + a] += r * u[a];
        for (int b = 0; b < 3; ++b) {
          const double w = u[a] * u[b];
          entries.emplace_back(3 * i + a, 3 * i + b, w);
          entries.emplace_back(3 * j + a, 3 * j + b, w);
          entries.emplace_back(3 * i + a, 3 * j + b, -w);
          entries.emplace_back(3 * j + a, 3 * i + b, -w);
        }
      }
    }
    // Rounding of a length is ~1e-16 of it; stop an order above.
    if (residual <= 1e-15) break;
    // The six rigid motions leave every length as it is: a small damping keeps the step off them.
    for (Eigen::Index k = 0; k < unknowns; ++k) entries.emplace_back(k, k, kRigidDamping);
    Eigen::SparseMatrix<double> normal(unknowns, unknowns);
    normal.setFromTriplets(entries.begin(), entries.end());
    if (!ldlt.factorize(std::move(normal))) break;
    const Eigen::VectorXd step = ldlt.solver().solve(rhs);
    if (!step.allFinite()) break;
    for (Eigen::Index v = 0; v < g.vertices.rows(); ++v)
      g.vertices.row(v) += step.segment<3>(3 * v).transpose();
  }
  const IntrinsicTriangulation& T = g.triangulation;
  std::size_t e = 0;
  for (int h = 0; h < T.halfedgeCount(); ++h)
    if (h < T.twin(h)) edges[e++].fold = foldOf(g, h);
  return (g.vertices - start).rowwise().norm().maxCoeff();
}

Result<std::vector<BodyEdge>> traceBodyEdges(const ExactGluing& g, double snap) {
  std::vector<BodyEdge> out;
  if (g.doublyCovered) return out;
  const IntrinsicTriangulation& T = g.triangulation;
  const Walker walker(g);
  for (int h = 0; h < T.halfedgeCount(); ++h) {
    const int t = T.twin(h);
    if (h > t) continue;
    BodyEdge edge;
    edge.from = g.seamOfVertex[T.tail(h)];
    edge.to = g.seamOfVertex[T.head(h)];
    edge.length = T.length(h);
    edge.fold = foldOf(g, h);
    if (Status s = walker.trace(h, snap, edge); !s.isOk()) return s;
    walker.straighten(edge);
    out.push_back(std::move(edge));
  }
  return out;
}

}  // namespace dform::exact
