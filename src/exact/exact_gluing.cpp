// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/exact/exact_gluing.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <list>
#include <numeric>

#include "plane_angles.h"

namespace dform::exact {

namespace {

using plane::ccwAngle;
using plane::cross;

Eigen::Vector2d row(const Points2& P, long k) {
  const long n = P.rows();
  return P.row(((k % n) + n) % n).transpose();
}

double bboxDiagonal(const Points2& P) {
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
}

// The sine of the turn at point k of P, from chord k - 1 to chord k (> 0: forwards, convex).
double turnSine(const Points2& P, long k) {
  const Eigen::Vector2d in = row(P, k) - row(P, k - 1), out = row(P, k + 1) - row(P, k);
  return cross(in, out) / (in.norm() * out.norm());
}

// Whether point k of P lies on the straight line through its two neighbours, to within
// kFlatCurvature, turning forwards.
bool onStraightLine(const Points2& P, long k) {
  return (row(P, k) - row(P, k - 1)).dot(row(P, k + 1) - row(P, k)) > 0.0 &&
         std::abs(turnSine(P, k)) <= kFlatCurvature;
}

// Least-norm Gauss-Newton: moves P so that |P[k+1] - P[k]| = target[k], and so that each point
// of `straight` stays on the straight line through its two neighbours (the sine of its turn
// stays 0).
double fitChords(Points2& P, const Eigen::VectorXd& target, const std::vector<int>& straight) {
  const int n = int(P.rows());
  const int rows = n + int(straight.size());
  const Points2 start = P;
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::VectorXd g(rows);
    std::vector<Eigen::Vector2d> u(n);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d e = row(P, k + 1) - row(P, k);
      g[k] = e.norm() - target[k];
      u[k] = e / e.norm();
    }
    // Row n + s: the turn's sine at straight[s], with its gradient in the three points (previous,
    // itself, next): d cross(a, b) = (b.y, -b.x) . da + (-a.y, a.x) . db over |a| |b|.
    std::vector<std::array<Eigen::Vector2d, 3>> bend(straight.size());
    double bent = 0.0;
    for (std::size_t s = 0; s < straight.size(); ++s) {
      const int k = straight[s];
      const Eigen::Vector2d a = row(P, k) - row(P, k - 1), b = row(P, k + 1) - row(P, k);
      const double scale = 1.0 / (a.norm() * b.norm());
      g[n + long(s)] = cross(a, b) * scale;
      bent = std::max(bent, std::abs(g[n + long(s)]));
      const Eigen::Vector2d da = Eigen::Vector2d(b.y(), -b.x()) * scale;
      const Eigen::Vector2d db = Eigen::Vector2d(-a.y(), a.x()) * scale;
      bend[s] = {-da, da - db, db};
    }
    // Rounding of a chord length is ~1e-16 of it; stop an order above.
    if (g.head(n).cwiseAbs().maxCoeff() <= 1e-15 * target.maxCoeff() && bent <= 1e-15) break;
    // J J^T of the constraints: 2 on the diagonal, -u_k . u_(k+1) between neighbouring chords;
    // a straight point's row meets the chords and straight points it shares a point with.
    std::vector<Eigen::Triplet<double>> entries;
    for (int k = 0; k < n; ++k) {
      entries.emplace_back(k, k, 2.0);
      const double off = -u[k].dot(u[(k + 1) % n]);
      entries.emplace_back(k, (k + 1) % n, off);
      entries.emplace_back((k + 1) % n, k, off);
    }
    // The gradient of chord c in point q: -u_c at its tail, u_c at its head.
    auto chordIn = [&](int c, int q) -> Eigen::Vector2d {
      const int tail = (c % n + n) % n;
      return q == tail ? Eigen::Vector2d(-u[tail]) : Eigen::Vector2d(u[tail]);
    };
    for (std::size_t s = 0; s < straight.size(); ++s) {
      const int k = straight[s], r = n + int(s);
      const int at[3] = {(k + n - 1) % n, k, (k + 1) % n};
      for (int c : {k - 2, k - 1, k, k + 1}) {  // the chords that touch its three points
        double v = 0.0;
        for (int j = 0; j < 3; ++j)
          if (at[j] == (c % n + n) % n || at[j] == ((c + 1) % n + n) % n)
            v += bend[s][std::size_t(j)].dot(chordIn(c, at[j]));
        const int col = (c % n + n) % n;
        if (v != 0.0) entries.emplace_back(r, col, v), entries.emplace_back(col, r, v);
      }
      // The straight points within two of it (straight is sorted) share a point with it.
      std::vector<std::size_t> near;
      for (long d = -2; d <= 2; ++d)
        near.push_back(
            std::size_t((long(s) + d + 5 * long(straight.size())) % long(straight.size())));
      std::sort(near.begin(), near.end());
      near.erase(std::unique(near.begin(), near.end()), near.end());
      for (std::size_t t : near) {
        const int m = straight[t];
        double v = 0.0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (at[i] == (m + j - 1 + n) % n)
              v += bend[s][std::size_t(i)].dot(bend[t][std::size_t(j)]);
        if (v != 0.0) entries.emplace_back(r, n + int(t), v);
      }
    }
    Eigen::SparseMatrix<double> JJt(rows, rows);
    JJt.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(JJt);
    if (solver.info() != Eigen::Success) break;
    const Eigen::VectorXd y = solver.solve(g);
    // delta = -J^T y: chord k pulls vertex k + 1 along u_k and pushes vertex k back; a straight
    // point's row moves its three points along its gradients.
    for (int k = 0; k < n; ++k) {
      P.row((k + 1) % n) -= y[k] * u[k].transpose();
      P.row(k) += y[k] * u[k].transpose();
    }
    for (std::size_t s = 0; s < straight.size(); ++s) {
      const int k = straight[s];
      for (int j = 0; j < 3; ++j)
        P.row((k + j - 1 + n) % n) -= y[n + long(s)] * bend[s][std::size_t(j)].transpose();
    }
  }
  return (P - start).rowwise().norm().maxCoeff();
}

// Triangulates the simple counter-clockwise polygon whose vertices are `loop` (indices into P) by
// clipping ears. No vertex may lie in an ear or on its new diagonal, to within kFlatCurvature
// seen from the diagonal's ends: the points of a straight side, which rounding leaves a little
// convex or reflex, would otherwise let an ear's diagonal run along the side and leave a polygon
// without area there.
std::vector<Eigen::Vector3i> earClip(const Points2& P, std::vector<int> loop) {
  std::vector<Eigen::Vector3i> out;
  std::list<int> ring(loop.begin(), loop.end());
  auto prevOf = [&](std::list<int>::iterator it) {
    return it == ring.begin() ? std::prev(ring.end()) : std::prev(it);
  };
  auto nextOf = [&](std::list<int>::iterator it) {
    auto n = std::next(it);
    return n == ring.end() ? ring.begin() : n;
  };
  // Whether p lies left of the line from x to y, or on it to within kFlatCurvature seen from x.
  auto leftOrOn = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y, const Eigen::Vector2d& p) {
    const double z = cross(y - x, p - x);
    return z >= 0.0 || z >= -kFlatCurvature * (y - x).norm() * (p - x).norm();
  };
  auto isEar = [&](std::list<int>::iterator it) {
    const Eigen::Vector2d a = P.row(*prevOf(it)), b = P.row(*it), c = P.row(*nextOf(it));
    if (!(cross(b - a, c - b) > 0.0)) return false;
    for (auto jt = ring.begin(); jt != ring.end(); ++jt) {
      if (jt == it || jt == prevOf(it) || jt == nextOf(it)) continue;
      const Eigen::Vector2d p = P.row(*jt);
      if (leftOrOn(a, b, p) && leftOrOn(b, c, p) && leftOrOn(c, a, p)) return false;
    }
    return true;
  };
  auto it = ring.begin();
  std::size_t sinceLastEar = 0;
  while (ring.size() > 3 && sinceLastEar < ring.size()) {
    if (isEar(it)) {
      out.emplace_back(*prevOf(it), *it, *nextOf(it));
      const auto after = nextOf(it);
      ring.erase(it);
      it = after;
      sinceLastEar = 0;
    } else {
      it = nextOf(it);
      ++sinceLastEar;
    }
  }
  if (ring.size() == 3) {
    auto first = ring.begin();
    out.emplace_back(*first, *std::next(first), *std::next(first, 2));
  }
  return out;
}

// The orientation-reversing isometry of B's plane onto A's that maps every b_k closest to a_k
// (least squares), and the largest distance left between a point and its image, mm; infinite
// where only a reflection of the reflected piece would fit.
double congruentMirror(const SeamPolygons& seam, Eigen::Matrix2d& M, Eigen::Vector2d& t) {
  const Eigen::Matrix2d mirror = Eigen::Vector2d(1.0, -1.0).asDiagonal();
  const Points2 b = seam.b * mirror;
  const Eigen::RowVector2d ca = seam.a.colwise().mean(), cb = b.colwise().mean();
  const Eigen::Matrix2d H = (b.rowwise() - cb).transpose() * (seam.a.rowwise() - ca);
  Eigen::JacobiSVD<Eigen::Matrix2d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d R = svd.matrixV() * svd.matrixU().transpose();
  if (R.determinant() < 0) return std::numeric_limits<double>::infinity();
  M = R * mirror;
  t = ca.transpose() - M * (seam.b.colwise().mean().transpose());
  const Points2 mapped = (seam.b * M.transpose()).rowwise() + t.transpose();
  return (mapped - seam.a).rowwise().norm().maxCoeff();
}

// The glued body's thickness: the extent of its vertices along their direction of least spread.
double thickness(const Eigen::MatrixX3d& V) {
  const Eigen::RowVector3d centre = V.colwise().mean();
  const Eigen::MatrixX3d centred = V.rowwise() - centre;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(centred.transpose() * centred);
  const Eigen::VectorXd along = centred * spread.eigenvectors().col(0);
  return along.maxCoeff() - along.minCoeff();
}

// Seam point k's direction towards q of piece `piece` as a signpost angle at k (A's wedge first,
// from chord k -> k + 1; then B's, from chord k -> k - 1), and whether q lies in that wedge.
bool directionTo(const ExactGluing& g, int piece, int k, const Eigen::Vector2d& q, double& angle) {
  const double slack = 1e-12;
  if (piece == 0) {
    const Eigen::Vector2d s = row(g.seam.a, k);
    double phi = ccwAngle(row(g.seam.a, k + 1) - s, q - s);
    if (phi > g.angles.a[k] + slack) {
      // Just below the chord by rounding reads as almost 2 pi.
      if (phi < 2.0 * kPi - slack) return false;
      phi = 0.0;
    }
    angle = std::min(phi, g.angles.a[k]);
  } else {
    const Eigen::Vector2d s = row(g.seam.b, k);
    double phi = ccwAngle(row(g.seam.b, k - 1) - s, q - s);
    if (phi > g.angles.b[k] + slack) {
      if (phi < 2.0 * kPi - slack) return false;
      phi = 0.0;
    }
    angle = g.angles.a[k] + std::min(phi, g.angles.b[k]);
  }
  return true;
}

// Whether the segment from seam point k to q crosses the polygon's boundary (q inside or on it).
bool crossesBoundary(const Points2& P, int k, const Eigen::Vector2d& q) {
  const long n = P.rows();
  const Eigen::Vector2d s = row(P, k);
  const Eigen::Vector2d d = q - s;
  const double scale = d.squaredNorm();
  for (long m = 0; m < n; ++m) {
    if (m == k || (m + 1) % n == k) continue;
    const Eigen::Vector2d p0 = row(P, m), p1 = row(P, m + 1);
    const double eps = 1e-12 * std::max(scale, (p1 - p0).squaredNorm());
    const double o1 = cross(d, p0 - s), o2 = cross(d, p1 - s);
    const double o3 = cross(p1 - p0, s - p0), o4 = cross(p1 - p0, q - p0);
    if (((o1 > eps && o2 < -eps) || (o1 < -eps && o2 > eps)) &&
        ((o3 > eps && o4 < -eps) || (o3 < -eps && o4 > eps)))
      return true;
  }
  return false;
}

// The doubly covered piece A: B's seam points are put on the mirror images of A's (moved by at
// most g.flatDeviation), so that the two pieces are congruent to rounding and every edge of the
// pouch keeps its length on both.
ExactGluing pressedFlat(ExactGluing g, ExactGluing::Pouch why) {
  g.doublyCovered = true;
  g.pouch = why;
  g.seam.b = (g.seam.a.rowwise() - g.flatShift.transpose()) * g.flatRotation;
  g.angles = seamAngles(g.seam);
  return g;
}

}  // namespace

namespace {

// Chord k of each polygon set to the mean of the two lengths, each polygon kept convex where it
// is (a point that turns forwards, or is straight, does not turn backwards); returns the largest
// move. Points on a straight line stay on it; a point that would turn backwards is kept straight
// instead, and the fit is made again (free, the points beside a corner, or where a side meets a
// curve, would leave the side's line, and those of the side next to them turn backwards: a metric
// that is not convex where the pieces are).
double fitMeanChords(SeamPolygons& seam) {
  const long n = seam.a.rows();
  Eigen::VectorXd target(n);
  for (long k = 0; k < n; ++k)
    target[k] = 0.5 * ((row(seam.a, k + 1) - row(seam.a, k)).norm() +
                       (row(seam.b, k + 1) - row(seam.b, k)).norm());
  double moved = 0.0;
  for (const auto& [P, forwards] : {std::pair{&seam.a, 1.0}, std::pair{&seam.b, -1.0}}) {
    // A runs counter-clockwise round its piece, B clockwise: B turns forwards with a negative sine.
    std::vector<int> straight;
    std::vector<bool> convex(static_cast<std::size_t>(n), false);
    for (long k = 0; k < n; ++k) {
      if (onStraightLine(*P, k)) straight.push_back(int(k));
      convex[std::size_t(k)] = forwards * turnSine(*P, k) >= -kFlatCurvature;
    }
    Points2 fitted = *P;
    for (int round = 0; round < 8; ++round) {
      fitted = *P;
      fitChords(fitted, target, straight);
      std::vector<int> backwards;
      for (long k = 0; k < n; ++k)
        if (convex[std::size_t(k)] && forwards * turnSine(fitted, k) < -kFlatCurvature)
          backwards.push_back(int(k));
      if (backwards.empty()) break;
      straight.insert(straight.end(), backwards.begin(), backwards.end());
      std::sort(straight.begin(), straight.end());
      straight.erase(std::unique(straight.begin(), straight.end()), straight.end());
    }
    moved = std::max(moved, (fitted - *P).rowwise().norm().maxCoeff());
    *P = fitted;
  }
  return moved;
}

// Straightens, on both sides, every run of seam points where both pieces turn by at most
// kSamplingExcess that holds one whose angle sum exceeds 2 pi by more than `from`: the run's points
// go onto the line through the two points around it, which take its turn, where those two turn
// forwards by more than the run turns backwards. Returns whether a point moved.
bool straightenRuns(SeamPolygons& seam, double from) {
  const SeamAngles angles = seamAngles(seam);
  const long n = seam.a.rows();
  // Nearly straight on both sides (each piece turns by at most kSamplingExcess there).
  auto small = [&](long k) {
    const long i = (k % n + n) % n;
    return std::abs(angles.a[i] - kPi) <= kSamplingExcess &&
           std::abs(angles.b[i] - kPi) <= kSamplingExcess;
  };
  std::vector<bool> done(std::size_t(n), false);
  bool moved = false;
  for (long k = 0; k < n; ++k) {
    const double c = angles.curvature[k];
    if (done[std::size_t(k)] || !(c < -from && small(k))) continue;
    long lo = k, hi = k;
    while (small(lo - 1) && hi - lo < n - 3) --lo;
    while (small(hi + 1) && hi - lo < n - 3) ++hi;
    double sum = 0.0;
    for (long j = lo - 1; j <= hi + 1; ++j) sum += angles.curvature[(j % n + n) % n];
    for (long j = lo; j <= hi; ++j) done[std::size_t((j % n + n) % n)] = true;
    if (!(sum > 0.0)) continue;  // a saddle of the metric, not a sampling artefact
    for (Points2* P : {&seam.a, &seam.b}) {
      const Eigen::Vector2d p0 = row(*P, lo - 1), u = (row(*P, hi + 1) - p0).normalized();
      for (long j = lo; j <= hi; ++j) {
        const Eigen::Vector2d q = row(*P, j);
        P->row((j % n + n) % n) = (p0 + u * u.dot(q - p0)).transpose();
      }
    }
    moved = true;
  }
  return moved;
}

}  // namespace

double equalizeChords(SeamPolygons& seam) {
  const SeamPolygons start = seam;
  fitMeanChords(seam);
  // A seam point whose two angles sum to a little more than 2 pi among points that turn forwards
  // by more is an artefact of sampling, not a saddle of the metric: samples on a flattened curve
  // (SVG arcs become chords ~2 mm long), moved off it for the chord loss, turn at the
  // flattening's corners and slightly backwards beside them (seen: 360.012 degrees on the
  // ellipse pair at n = 500, 360.133 on two circles at n = 800). The nearly straight run holding
  // it is made straight on both sides (moves well under a micrometre), its turn going to the
  // points around it; a real saddle is left for glue to refuse. Equal chords again leave the run
  // off its line by ~1e-8 rad, so it is put back once more without refitting (the chords change
  // by ~angle^2 x chord, below rounding).
  for (int round = 0; round < 4 && straightenRuns(seam, kFlatCurvature); ++round)
    fitMeanChords(seam);
  straightenRuns(seam, kFlatCurvature);
  return std::max((seam.a - start.a).rowwise().norm().maxCoeff(),
                  (seam.b - start.b).rowwise().norm().maxCoeff());
}

double seamPrecision(const SeamPolygons& seam) {
  return std::max(kOutlinePrecision, 1e-6 * std::max(bboxDiagonal(seam.a), bboxDiagonal(seam.b)));
}

SeamAngles seamAngles(const SeamPolygons& seam) {
  const long n = seam.a.rows();
  SeamAngles out;
  out.a.resize(n);
  out.b.resize(n);
  for (long k = 0; k < n; ++k) {
    out.a[k] = ccwAngle(row(seam.a, k + 1) - row(seam.a, k), row(seam.a, k - 1) - row(seam.a, k));
    out.b[k] = ccwAngle(row(seam.b, k - 1) - row(seam.b, k), row(seam.b, k + 1) - row(seam.b, k));
  }
  out.curvature = (2.0 * kPi - out.a.array() - out.b.array()).matrix();
  for (long k = 0; k < n && out.firstNonConvex < 0; ++k)
    if (out.curvature[k] < -kFlatCurvature) out.firstNonConvex = int(k);
  return out;
}

Result<ExactGluing> glue(const SeamPolygons& seam, const ExactOptions& options) {
  ExactGluing g;
  g.seam = seam;
  g.angles = seamAngles(seam);
  const int n = int(seam.a.rows());
  if (g.angles.firstNonConvex >= 0) {
    const int k = g.angles.firstNonConvex;
    return Status(ErrorCode::InputInvalid,
                  "the glued metric is not convex: at seam point " + std::to_string(k) +
                      " the two pieces' angles sum to " +
                      std::to_string((g.angles.a[k] + g.angles.b[k]) * 180.0 / kPi) +
                      " degrees, more than 360");
  }
  // Congruent pieces zipped point to point fold flat: Alexandrov's body is the doubly covered
  // piece, with no inside for an apex. Congruent to the precision the outlines are known to.
  const double size = std::max(bboxDiagonal(seam.a), bboxDiagonal(seam.b));
  const double precision = seamPrecision(seam);
  g.flatDeviation = congruentMirror(seam, g.flatRotation, g.flatShift);
  if (g.flatDeviation <= precision) return pressedFlat(std::move(g), ExactGluing::Pouch::Congruent);
  // The surface: both pieces triangulated without inner points and glued along the chords. A
  // seam point on a straight side of both pieces is no vertex of either polygon (its two chords
  // are one straight chord on each side); other flat points are removed from the triangulation.
  auto straight = [](double angle) { return std::abs(angle - kPi) <= kFlatCurvature; };
  std::vector<int> loopA, loopB;
  for (int k = 0; k < n; ++k)
    if (!(straight(g.angles.a[k]) && straight(g.angles.b[k]))) loopA.push_back(k);
  const int m = int(loopA.size());
  if (m < 4)
    return Status(ErrorCode::InputInvalid, "the glued surface has fewer than four cone points");
  loopB.assign(loopA.rbegin(), loopA.rend());  // B counter-clockwise in its plane
  std::vector<int> nextKept(n);
  for (int i = 0; i < m; ++i) nextKept[loopA[i]] = loopA[(i + 1) % m];
  const std::vector<Eigen::Vector3i> facesA = earClip(seam.a, loopA),
                                     facesB = earClip(seam.b, loopB);
  if (int(facesA.size()) != m - 2 || int(facesB.size()) != m - 2)
    return Status(ErrorCode::InputInvalid, "a piece's seam polygon is not simple");
  const int nF = 2 * m - 4;
  Eigen::MatrixX3i F(nF, 3);
  Eigen::MatrixX3d L(nF, 3), S(nF, 3);
  std::vector<int> pieceOfFace(nF);
  for (int f = 0; f < nF; ++f) {
    const int piece = f < m - 2 ? 0 : 1;
    pieceOfFace[f] = piece;
    const Eigen::Vector3i face = piece == 0 ? facesA[f] : facesB[f - (m - 2)];
    const Points2& P = piece == 0 ? seam.a : seam.b;
    F.row(f) = face.transpose();
    for (int c = 0; c < 3; ++c) {
      const int i = face[c], j = face[(c + 1) % 3];
      L(f, c) = (P.row(j) - P.row(i)).norm();
      double angle = 0;
      directionTo(g, piece, i, P.row(j).transpose(), angle);
      S(f, c) = angle;
      // A chord's two sides get one length (equal after equalizeChords up to rounding).
      if (nextKept[i] == j || nextKept[j] == i) {
        const int k = nextKept[i] == j ? i : j, l = nextKept[k];
        L(f, c) = 0.5 * ((row(seam.a, l) - row(seam.a, k)).norm() +
                         (row(seam.b, l) - row(seam.b, k)).norm());
      }
    }
  }
  std::vector<double> cones(n);
  for (int k = 0; k < n; ++k) cones[k] = g.angles.a[k] + g.angles.b[k];
  IntrinsicTriangulation tri(F, L, S, cones, pieceOfFace);
  for (int k : loopA)
    if (std::abs(g.angles.curvature[k]) <= kFlatCurvature && !tri.removeFlatVertex(k))
      return Status(ErrorCode::SolveFailed,
                    "seam point " + std::to_string(k) + " is flat but could not be removed");
  g.vertexOfSeam = tri.compact();
  g.seamOfVertex.assign(tri.vertexCount(), -1);
  for (int k = 0; k < n; ++k)
    if (g.vertexOfSeam[k] >= 0) g.seamOfVertex[g.vertexOfSeam[k]] = k;
  g.embedding = embedConvex(tri, options.embedding);
  if (!g.embedding.converged)
    return Status(ErrorCode::SolveFailed,
                  "the exact gluing did not converge: " + g.embedding.message);
  // A body thinner than pressing it flat would change a length of it by the precision (a path
  // over its width W rising h is longer by about 2 h^2 / W) is the doubly covered piece: the
  // pieces are congruent as far as their outlines are known, zipped point to point (drawn with
  // rounded coordinates, say), and its two sheets, micrometres apart, would fold within a
  // precision of the seam. (Laid out by chained triangles, so thin a body reads its edges a few
  // millionths off.)
  if (const double h = thickness(g.embedding.vertices);
      h <= std::sqrt(0.5 * precision * size) &&
      g.flatDeviation <= std::sqrt(0.5 * precision * size)) {
    g.thickness = h;
    return pressedFlat(std::move(g), ExactGluing::Pouch::Thin);
  }
  // Laid out in 3D, every edge keeps its length to ~1e-10 where the layout is sound (tests/exact).
  if (!(g.embedding.maxEdgeError <= 1e-6))
    return Status(ErrorCode::SolveFailed,
                  "the exact body's vertices could not be laid out consistently (an edge off by " +
                      std::to_string(100 * g.embedding.maxEdgeError) + " %)");
  g.vertices = g.embedding.vertices;
  g.triangulation = std::move(tri);
  return g;
}

Points3 placeOnBody(const ExactGluing& g, int piece, const Points2& P) {
  const Points2& polygon = piece == 0 ? g.seam.a : g.seam.b;
  Points3 out(P.rows(), 3);
  if (g.doublyCovered) {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d q = piece == 0 ? Eigen::Vector2d(P.row(i))
                                           : g.flatRotation * P.row(i).transpose() + g.flatShift;
      out.row(i) << q.x(), q.y(), 0.0;
    }
    return out;
  }
  std::vector<int> cones;
  for (std::size_t k = 0; k < g.vertexOfSeam.size(); ++k)
    if (g.vertexOfSeam[k] >= 0) cones.push_back(int(k));
  const double size = bboxDiagonal(polygon);
  std::vector<std::pair<double, int>> byDistance(cones.size());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector2d q = P.row(i).transpose();
    out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
    for (std::size_t c = 0; c < cones.size(); ++c)
      byDistance[c] = {(row(polygon, cones[c]) - q).norm(), cones[c]};
    // Nearest cone first, then the next nearest, each found when needed: the nearest one almost
    // always places the point, and sorting every cone for every point would cost more than placing
    // it.
    for (auto untried = byDistance.begin(); untried != byDistance.end(); ++untried) {
      std::iter_swap(untried, std::min_element(untried, byDistance.end()));
      const auto [distance, k] = *untried;
      const int v = g.vertexOfSeam[k];
      if (distance <= 1e-12 * size) {
        out.row(i) = g.vertices.row(v);
        break;
      }
      double angle = 0;
      if (!directionTo(g, piece, k, q, angle) || crossesBoundary(polygon, k, q)) continue;
      const SurfacePoint at = g.triangulation.trace(v, angle, distance);
      if (at.face < 0) continue;
      Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
      for (int c = 0; c < 3; ++c)
        x += at.bary[c] * g.vertices.row(g.triangulation.tail(3 * at.face + c));
      out.row(i) = x;
      break;
    }
  }
  return out;
}

}  // namespace dform::exact
