// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/exact/alexandrov.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <unsupported/Eigen/AutoDiff>

#include "dform/core/constants.h"
#include "dform/core/pattern_ldlt.h"

namespace dform::exact {

namespace {

using Dual = Eigen::AutoDiffScalar<Eigen::Vector3d>;

// A face laid out in the plane: corner 0 at the origin, corner 1 on the +x axis, corner 2 above.
struct FaceLayout {
  Eigen::Vector2d v[3];
};

FaceLayout layout(const IntrinsicTriangulation& tri, int f) {
  const double l0 = tri.length(3 * f), l1 = tri.length(3 * f + 1), l2 = tri.length(3 * f + 2);
  FaceLayout out;
  out.v[0] = Eigen::Vector2d(0, 0);
  out.v[1] = Eigen::Vector2d(l0, 0);
  const double x = (l0 * l0 + l2 * l2 - l1 * l1) / (2.0 * l0);
  out.v[2] = Eigen::Vector2d(x, std::sqrt(std::max(0.0, l2 * l2 - x * x)));
  return out;
}

// The apex's foot on the face plane (the power centre of the corners with weights r^2), and the
// apex's squared height above it.
template <typename S>
void apexFoot(const FaceLayout& L, const S r[3], S& qx, S& qy, S& h2) {
  const Eigen::Vector2d& v1 = L.v[1];
  const Eigen::Vector2d& v2 = L.v[2];
  qx = (v1.x() * v1.x() + r[0] * r[0] - r[1] * r[1]) / (2.0 * v1.x());
  qy = ((v2.squaredNorm() + r[0] * r[0] - r[2] * r[2]) / 2.0 - qx * v2.x()) / v2.y();
  h2 = r[0] * r[0] - qx * qx - qy * qy;
}

// The dihedral angles of the tetrahedron (apex, corner 0, 1, 2) at its three radial edges.
template <typename S>
void radialDihedrals(const FaceLayout& L, const S r[3], S omega[3], S& h2) {
  S qx, qy;
  apexFoot(L, r, qx, qy, h2);
  using std::atan2;
  using std::sqrt;
  const S h = sqrt(h2);
  // Corner c relative to the apex.
  S X[3][3];
  for (int c = 0; c < 3; ++c) {
    X[c][0] = L.v[c].x() - qx;
    X[c][1] = L.v[c].y() - qy;
    X[c][2] = -h;
  }
  for (int c = 0; c < 3; ++c) {
    const S* e = X[c];
    const S* a = X[(c + 1) % 3];
    const S* b = X[(c + 2) % 3];
    const S ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const S ae = (a[0] * e[0] + a[1] * e[1] + a[2] * e[2]) / ee;
    const S be = (b[0] * e[0] + b[1] * e[1] + b[2] * e[2]) / ee;
    S ap[3], bp[3];
    for (int k = 0; k < 3; ++k) {
      ap[k] = a[k] - ae * e[k];
      bp[k] = b[k] - be * e[k];
    }
    const S cx = ap[1] * bp[2] - ap[2] * bp[1];
    const S cy = ap[2] * bp[0] - ap[0] * bp[2];
    const S cz = ap[0] * bp[1] - ap[1] * bp[0];
    omega[c] =
        atan2(sqrt(cx * cx + cy * cy + cz * cz), ap[0] * bp[0] + ap[1] * bp[1] + ap[2] * bp[2]);
  }
}

// Whether the edge of h is locally regular: the vertex across it lies outside the orthogonal
// sphere of h's face, |q - v_l|^2 - r_l^2 >= |q - v_i|^2 - r_i^2 (for equal radii, Delaunay).
// `slack` is how far past it (mm^2) still counts as regular.
bool locallyRegular(const IntrinsicTriangulation& tri, const Eigen::VectorXd& r, int h,
                    double slack) {
  const int f = h / 3, c = h % 3;
  const FaceLayout L = layout(tri, f);
  double rr[3];
  for (int k = 0; k < 3; ++k) rr[k] = r[tri.tail(3 * f + k)];
  double qx, qy, h2;
  apexFoot(L, rr, qx, qy, h2);
  // The far vertex of the twin face, unfolded across the edge from corner c to c + 1.
  const int t = tri.twin(h);
  const Eigen::Vector2d p = L.v[(c + 1) % 3], q = L.v[c];  // t runs p -> q
  const double pq = (q - p).norm();
  const double lq = tri.length(IntrinsicTriangulation::next(t)),
               lp = tri.length(IntrinsicTriangulation::prev(t));
  const double x = (pq * pq + lp * lp - lq * lq) / (2.0 * pq);
  const double y = std::sqrt(std::max(0.0, lp * lp - x * x));
  const Eigen::Vector2d u = (q - p) / pq;
  const Eigen::Vector2d far = p + x * u + y * Eigen::Vector2d(-u.y(), u.x());
  const int l = tri.tail(IntrinsicTriangulation::prev(t));
  const Eigen::Vector2d foot(qx, qy);
  const double powerFar = (foot - far).squaredNorm() - r[l] * r[l];
  const double powerFace = (foot - L.v[c]).squaredNorm() - rr[c] * rr[c];
  return powerFar >= powerFace - slack;
}

// The point X with |X| = rl, |X - A| = la, |X - B| = lb on the side where det(B, A, X) > 0.
Eigen::Vector3d trilaterate(const Eigen::Vector3d& A, const Eigen::Vector3d& B, double rl,
                            double la, double lb) {
  const double a = 0.5 * (rl * rl + A.squaredNorm() - la * la);
  const double b = 0.5 * (rl * rl + B.squaredNorm() - lb * lb);
  Eigen::Matrix2d G;
  G << A.dot(A), A.dot(B), A.dot(B), B.dot(B);
  const Eigen::Vector2d ab = G.inverse() * Eigen::Vector2d(a, b);
  const Eigen::Vector3d inPlane = ab[0] * A + ab[1] * B;
  const Eigen::Vector3d n = A.cross(B).normalized();
  const double gamma = std::sqrt(std::max(0.0, rl * rl - inPlane.squaredNorm()));
  return inPlane - gamma * n;  // det(B, A, X) = -X . (A x B) > 0
}

// Places every vertex with the apex at the origin: a first face from its tetrahedron, then one
// vertex at a time from a face whose other two corners are placed. Each placement solves with
// the Gram matrix of those two corners' radial vectors, which is ill-conditioned when they are
// nearly parallel (a short edge seen from far: 4 mm at 50 mm amplifies errors 150 times), and
// errors compound from vertex to vertex; so each step takes the face whose two placed radial
// vectors are furthest from parallel.
Eigen::MatrixX3d placeVertices(const IntrinsicTriangulation& tri, const Eigen::VectorXd& r) {
  Eigen::MatrixX3d V = Eigen::MatrixX3d::Zero(tri.vertexCount(), 3);
  std::vector<bool> placed(tri.vertexCount(), false);
  const FaceLayout L = layout(tri, 0);
  double rr[3], qx, qy, h2;
  for (int k = 0; k < 3; ++k) rr[k] = r[tri.tail(k)];
  apexFoot(L, rr, qx, qy, h2);
  for (int k = 0; k < 3; ++k) {
    V.row(tri.tail(k)) =
        Eigen::RowVector3d(L.v[k].x() - qx, L.v[k].y() - qy, std::sqrt(std::max(0.0, h2)));
    placed[tri.tail(k)] = true;
  }
  for (int left = tri.vertexCount() - 3; left > 0; --left) {
    int bestHalfedge = -1;
    double bestSine = -1.0;
    for (int t = 0; t < tri.halfedgeCount(); ++t) {
      const int l = tri.tail(IntrinsicTriangulation::prev(t));
      if (placed[l] || !placed[tri.tail(t)] || !placed[tri.head(t)]) continue;
      const Eigen::Vector3d A = V.row(tri.head(t)), B = V.row(tri.tail(t));
      const double sine = A.cross(B).norm() / (A.norm() * B.norm());
      if (sine > bestSine) {
        bestSine = sine;
        bestHalfedge = t;
      }
    }
    if (bestHalfedge < 0) break;  // a disconnected triangulation: left unplaced (at the origin)
    // The face (j, i, l) with t running j -> i.
    const int t = bestHalfedge, j = tri.tail(t), i = tri.head(t),
              l = tri.tail(IntrinsicTriangulation::prev(t));
    V.row(l) = trilaterate(V.row(i).transpose(), V.row(j).transpose(), r[l],
                           tri.length(IntrinsicTriangulation::next(t)),
                           tri.length(IntrinsicTriangulation::prev(t)))
                   .transpose();
    placed[l] = true;
  }
  return V;
}

// The largest relative misfit of an edge of V against its length in `tri`.
double maxEdgeError(const IntrinsicTriangulation& tri, const Eigen::MatrixX3d& V) {
  double worst = 0.0;
  for (int h = 0; h < tri.halfedgeCount(); ++h) {
    const double l = (V.row(tri.tail(h)) - V.row(tri.head(h))).norm();
    worst = std::max(worst, std::abs(l - tri.length(h)) / tri.length(h));
  }
  return worst;
}

// Gauss-Newton on the laid-out vertices: every edge to its length and every vertex to its radius
// (residuals relative to them), all at once. Placing one vertex at a time compounds each step's
// rounding through the faces the chain crosses, nearly flat ones among them (seam points on a
// straight side, beside a cone of small curvature), into millionths of an edge at 1000 seam
// points; the lengths and radii themselves agree to the curvature reached (~1e-12), so a few
// steps bring every edge to rounding. A step is kept only where it lowers the largest misfit.
// The layout is fixed only up to a rotation about the apex, hence the small damping.
Eigen::MatrixX3d refineVertices(const IntrinsicTriangulation& tri, const Eigen::VectorXd& r,
                                Eigen::MatrixX3d V) {
  const int n = tri.vertexCount();
  std::vector<int> edges;  // one halfedge per edge
  for (int h = 0; h < tri.halfedgeCount(); ++h)
    if (tri.tail(h) < tri.head(h)) edges.push_back(h);
  double worst = maxEdgeError(tri, V);
  PatternLDLT ldlt;  // one pattern, the edges' and the radii's, at every step
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(std::size_t(4 * 9 * edges.size() + 9 * n + 3 * n));
  for (int step = 0; step < 4 && worst > 1e-13; ++step) {
    entries.clear();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * n);
    // One residual row: gradient u at vertex i and -u at vertex j (j < 0: the apex, fixed).
    auto add = [&](int i, int j, const Eigen::Vector3d& u, double residual) {
      const int at[2] = {i, j};
      const double sign[2] = {1.0, -1.0};
      for (int a = 0; a < 2; ++a) {
        if (at[a] < 0) continue;
        rhs.segment<3>(3 * at[a]) -= sign[a] * residual * u;
        for (int b = 0; b < 2; ++b) {
          if (at[b] < 0) continue;
          const Eigen::Matrix3d block = sign[a] * sign[b] * u * u.transpose();
          for (int x = 0; x < 3; ++x)
            for (int y = 0; y < 3; ++y)
              entries.emplace_back(3 * at[a] + x, 3 * at[b] + y, block(x, y));
        }
      }
    };
    for (int h : edges) {
      const int i = tri.tail(h), j = tri.head(h);
      const Eigen::Vector3d e = V.row(i) - V.row(j);
      const double l = tri.length(h);
      add(i, j, e / (e.norm() * l), e.norm() / l - 1.0);
    }
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = V.row(i);
      add(i, -1, x / (x.norm() * r[i]), x.norm() / r[i] - 1.0);
    }
    const double damping = 1e-12 / (r.maxCoeff() * r.maxCoeff());
    for (int k = 0; k < 3 * n; ++k) entries.emplace_back(k, k, damping);
    Eigen::SparseMatrix<double> JtJ(3 * n, 3 * n);
    JtJ.setFromTriplets(entries.begin(), entries.end());
    if (!ldlt.factorize(std::move(JtJ))) break;
    const Eigen::VectorXd delta = ldlt.solver().solve(rhs);
    Eigen::MatrixX3d moved = V;
    for (int i = 0; i < n; ++i) moved.row(i) += delta.segment<3>(3 * i).transpose();
    const double error = maxEdgeError(tri, moved);
    if (!(error < worst)) break;
    worst = error;
    V = std::move(moved);
  }
  return V;
}

}  // namespace

RadialCurvatures radialCurvatures(const IntrinsicTriangulation& tri, const Eigen::VectorXd& r) {
  const int n = tri.vertexCount();
  RadialCurvatures out;
  out.kappa = Eigen::VectorXd::Constant(n, 2.0 * kPi);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * tri.faceCount());
  out.minHeightSquared = 1e300;
  for (int f = 0; f < tri.faceCount(); ++f) {
    const FaceLayout L = layout(tri, f);
    Dual rr[3], omega[3], h2;
    int vertex[3];
    for (int k = 0; k < 3; ++k) {
      vertex[k] = tri.tail(3 * f + k);
      rr[k] = Dual(r[vertex[k]], 3, k);
    }
    // The apex must stand above the face by more than rounding of the squared lengths.
    double dummyX, dummyY, height2;
    const double rv[3] = {r[vertex[0]], r[vertex[1]], r[vertex[2]]};
    apexFoot(L, rv, dummyX, dummyY, height2);
    out.minHeightSquared = std::min(out.minHeightSquared, height2);
    if (!(height2 > 1e-12 * rv[0] * rv[0])) return out;
    radialDihedrals(L, rr, omega, h2);
    for (int k = 0; k < 3; ++k) {
      out.kappa[vertex[k]] -= omega[k].value();
      for (int m = 0; m < 3; ++m)
        entries.emplace_back(vertex[k], vertex[m], -omega[k].derivatives()[m]);
    }
  }
  out.jacobian.resize(n, n);
  out.jacobian.setFromTriplets(entries.begin(), entries.end());
  out.valid =
      out.kappa.allFinite() && Eigen::VectorXd(out.jacobian * Eigen::VectorXd::Ones(n)).allFinite();
  return out;
}

bool makeRegular(IntrinsicTriangulation& tri, const Eigen::VectorXd& r) {
  std::deque<int> queue;
  for (int h = 0; h < tri.halfedgeCount(); ++h)
    if (h < tri.twin(h)) queue.push_back(h);
  // Regularity is decided on squared lengths; allow their rounding.
  const double slack = 1e-12 * r.squaredNorm() / double(r.size());
  long flips = 0;
  const long bound = 100L * tri.halfedgeCount() + 1000;
  // An edge that must flip but spans a quadrilateral that is not convex may become flippable once
  // its neighbours have flipped: it waits until the queue is empty.
  std::vector<int> waiting;
  while (!queue.empty()) {
    const int h = queue.front();
    queue.pop_front();
    if (locallyRegular(tri, r, h, slack)) continue;
    if (!tri.flippable(h)) {
      waiting.push_back(h);
      if (queue.empty()) {
        bool anyFlippable = false;
        for (int w : waiting)
          anyFlippable = anyFlippable || (!locallyRegular(tri, r, w, slack) && tri.flippable(w));
        if (!anyFlippable) break;
        queue.insert(queue.end(), waiting.begin(), waiting.end());
        waiting.clear();
      }
      continue;
    }
    if (++flips > bound) return false;
    const int faces[2] = {h / 3, tri.twin(h) / 3};  // the flip keeps the two faces' indices
    tri.flip(h);
    for (int f : faces)
      for (int c = 0; c < 3; ++c) queue.push_back(3 * f + c);
  }
  for (int w : waiting)
    if (!locallyRegular(tri, r, w, slack)) return false;
  return true;
}

AlexandrovResult embedConvex(IntrinsicTriangulation& tri, const AlexandrovOptions& options) {
  AlexandrovResult result;
  const int n = tri.vertexCount();
  tri.makeDelaunay();
  // Equal radii larger than every circumradius stand the apex above every face of the Delaunay
  // triangulation, which is then also weighted Delaunay: the start of the deformation.
  double circumradius = 0.0;
  for (int f = 0; f < tri.faceCount(); ++f) {
    const double a = tri.length(3 * f), b = tri.length(3 * f + 1), c = tri.length(3 * f + 2);
    const double s = 0.5 * (a + b + c);
    const double area = std::sqrt(std::max(1e-300, s * (s - a) * (s - b) * (s - c)));
    circumradius = std::max(circumradius, a * b * c / (4.0 * area));
  }
  Eigen::VectorXd r = Eigen::VectorXd::Constant(n, 2.0 * circumradius);
  if (!makeRegular(tri, r)) {
    result.message = "the starting triangulation is not weighted Delaunay";
    return result;
  }
  RadialCurvatures current = radialCurvatures(tri, r);
  if (!current.valid) {
    result.message = "the starting radii do not stand the apex above every face";
    return result;
  }
  // Follow kappa(r) = t kappa(r_start) from t = 1 down to t = 0 (Bobenko and Izmestiev's
  // deformation): along it every curvature stays positive, so every vertex stays a vertex of the
  // weighted Delaunay triangulation, and the Jacobian (the Hessian of the Hilbert-Einstein
  // functional, one positive eigenvalue) stays invertible. Newton corrects to each target; the
  // step in t adapts to how far Newton can go while every tetrahedron stays valid.
  const Eigen::VectorXd kappaStart = current.kappa;
  double t = 1.0, dt = 0.25;
  // Flips change the pattern only now and then: its ordering is kept while it stays.
  PatternLDLT ldlt;
  auto newtonTo = [&](double target, double tolerance, int maxSteps) {
    for (int step = 0; step < maxSteps; ++step) {
      const Eigen::VectorXd residual = current.kappa - target * kappaStart;
      if (residual.cwiseAbs().maxCoeff() <= tolerance) return true;
      // Gauss-Newton with a damping far below J's spectrum: Newton's step while J is invertible,
      // and at t = 0, where moving the apex inside the body leaves every kappa at 0 (J has a
      // three-dimensional kernel), the least-norm step.
      const Eigen::SparseMatrix<double> JtJ =
          Eigen::SparseMatrix<double>(current.jacobian.transpose()) * current.jacobian;
      Eigen::SparseMatrix<double> damped = JtJ;
      const double mu = 1e-12 * JtJ.diagonal().sum() / double(JtJ.rows());
      for (int i = 0; i < damped.rows(); ++i) damped.coeffRef(i, i) += mu;
      ldlt.factorize(std::move(damped));
      const Eigen::VectorXd delta =
          -ldlt.solver().solve(Eigen::VectorXd(current.jacobian.transpose() * residual));
      if (!delta.allFinite()) return false;
      bool moved = false;
      for (double alpha = 1.0; alpha > 1.0 / 1024 && !moved; alpha /= 2) {
        const Eigen::VectorXd trialR = r + alpha * delta;
        if (trialR.minCoeff() <= 0.0) continue;
        IntrinsicTriangulation trialTri = tri;
        if (!makeRegular(trialTri, trialR)) continue;
        RadialCurvatures trial = radialCurvatures(trialTri, trialR);
        if (!trial.valid || (trial.kappa - target * kappaStart).norm() >= residual.norm()) continue;
        tri = std::move(trialTri);
        r = trialR;
        current = std::move(trial);
        moved = true;
      }
      ++result.iterations;
      if (!moved) return false;
    }
    return (current.kappa - target * kappaStart).cwiseAbs().maxCoeff() <= tolerance;
  };
  // On the way, each target is met to a fraction of the step in t: what is left over is
  // corrected at the next one.
  while (t > 0.0 && result.iterations < options.maxIterations) {
    const double next = std::max(0.0, t - dt);
    const IntrinsicTriangulation savedTri = tri;
    const Eigen::VectorXd savedR = r;
    const RadialCurvatures saved = current;
    const bool last = next == 0.0;
    const bool reached = newtonTo(
        next, last ? options.curvatureTolerance : 0.1 * dt * kappaStart.maxCoeff(), last ? 50 : 8);
    if (reached || (last && current.kappa.cwiseAbs().maxCoeff() <= options.acceptedCurvature)) {
      t = next;
      dt = std::min(1.0, 1.5 * dt);
    } else {
      tri = savedTri;
      r = savedR;
      current = saved;
      dt *= 0.25;
      if (dt < 1e-6) break;
    }
  }
  result.maxCurvature = current.kappa.cwiseAbs().maxCoeff();
  result.radii = r;
  result.converged = t == 0.0 && result.maxCurvature <= options.acceptedCurvature;
  if (!result.converged) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the curvatures stalled at %.3g rad (deformation at t = %.3g) after %d steps",
                  result.maxCurvature, t, result.iterations);
    result.message = text;
  }
  result.vertices = refineVertices(tri, r, placeVertices(tri, r));
  result.maxEdgeError = maxEdgeError(tri, result.vertices);
  return result;
}

}  // namespace dform::exact
