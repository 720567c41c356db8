// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/exact/intrinsic_triangulation.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <deque>

#include "dform/core/constants.h"
#include "plane_angles.h"

namespace dform::exact {

namespace {

using plane::cross;

// The third corner of a counter-clockwise triangle (p, q, r) given p, q and |q r|, |r p|.
Eigen::Vector2d thirdCorner(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double qr,
                            double rp) {
  const Eigen::Vector2d e = q - p;
  const double pq = e.norm();
  const double x = (pq * pq + rp * rp - qr * qr) / (2.0 * pq);
  const double y = std::sqrt(std::max(0.0, rp * rp - x * x));
  const Eigen::Vector2d u = e / pq;
  return p + x * u + y * Eigen::Vector2d(-u.y(), u.x());
}

// Barycentric coordinates of t in the triangle (p0, p1, p2).
Eigen::Vector3d barycentric(const Eigen::Vector2d P[3], const Eigen::Vector2d& t) {
  const double area = cross(P[1] - P[0], P[2] - P[0]);
  return Eigen::Vector3d(cross(P[1] - t, P[2] - t), cross(P[2] - t, P[0] - t),
                         cross(P[0] - t, P[1] - t)) /
         area;
}

}  // namespace

double triangleAngle(double ab, double bc, double ca) {
  const double c = (ab * ab + ca * ca - bc * bc) / (2.0 * ab * ca);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

IntrinsicTriangulation::IntrinsicTriangulation(const Eigen::MatrixX3i& faces,
                                               const Eigen::MatrixX3d& lengths,
                                               const Eigen::MatrixX3d& signposts,
                                               std::vector<double> coneAngles,
                                               const std::vector<int>& groups)
    : coneAngle_(std::move(coneAngles)) {
  const int nF = int(faces.rows());
  tail_.resize(3 * nF);
  twin_.assign(3 * nF, -1);
  length_.resize(3 * nF);
  signpost_.resize(3 * nF);
  vertexHalfedge_.assign(coneAngle_.size(), -1);
  std::vector<std::vector<int>> leaving(coneAngle_.size());
  for (int f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) {
      const int h = 3 * f + c;
      tail_[h] = faces(f, c);
      length_[h] = lengths(f, c);
      signpost_[h] = signposts(f, c);
      vertexHalfedge_[tail_[h]] = h;
      leaving[tail_[h]].push_back(h);
    }
  auto group = [&](int h) { return groups.empty() ? 0 : groups[h / 3]; };
  for (int h = 0; h < 3 * nF; ++h) {
    if (twin_[h] >= 0) continue;
    int match = -1;
    for (int g : leaving[head(h)])
      if (head(g) == tail_[h] && twin_[g] < 0 && (match < 0 || group(g) == group(h))) match = g;
    assert(match >= 0 && "every edge must have two sides");
    twin_[h] = match;
    twin_[match] = h;
  }
}

double IntrinsicTriangulation::cornerAngle(int h) const {
  return triangleAngle(length_[h], length_[next(h)], length_[prev(h)]);
}

std::vector<int> IntrinsicTriangulation::outgoing(int v) const {
  std::vector<int> out;
  const int first = vertexHalfedge_[v];
  int h = first;
  do {
    out.push_back(h);
    h = twin_[prev(h)];
  } while (h != first && out.size() <= tail_.size());
  return out;
}

bool IntrinsicTriangulation::flippable(int h, double* newLength) const {
  const int t = twin_[h];
  if (h / 3 == t / 3) return false;
  const int h1 = next(h), h2 = prev(h), t1 = next(t), t2 = prev(t);
  for (int o : {h1, h2, t1, t2}) {
    const int f = twin_[o] / 3;
    if (f == h / 3 || f == t / 3) return false;  // the two faces share a second edge
  }
  // Lay out a = (0, 0), b = (L, 0); c above the edge, d below.
  const Eigen::Vector2d a(0, 0), b(length_[h], 0);
  const Eigen::Vector2d c = thirdCorner(a, b, length_[h1], length_[h2]);
  const Eigen::Vector2d d = thirdCorner(b, a, length_[t1], length_[t2]);
  // Strictly convex: a and b on opposite sides of the new edge, each by a margin relative to it.
  const Eigen::Vector2d cd = d - c;
  const double margin = 1e-12 * cd.squaredNorm();
  if (!(cross(cd, a - c) < -margin && cross(cd, b - c) > margin)) return false;
  if (newLength) *newLength = cd.norm();
  return true;
}

void IntrinsicTriangulation::flip(int h) {
  double cd = 0.0;
  [[maybe_unused]] const bool ok = flippable(h, &cd);
  assert(ok && "flip of an edge that cannot be flipped");
  const int t = twin_[h];
  const int f1 = h / 3, f2 = t / 3;
  const int h1 = next(h), h2 = prev(h), t1 = next(t), t2 = prev(t);
  struct Side {
    int tail, twin;
    double length, signpost;
  };
  auto take = [&](int o) { return Side{tail_[o], twin_[o], length_[o], signpost_[o]}; };
  const Side sh1 = take(h1), sh2 = take(h2), st1 = take(t1), st2 = take(t2);
  const int a = tail_[h], b = tail_[t], c = sh2.tail, d = st2.tail;
  // New faces: f1 = (c, a, d), f2 = (d, b, c); the new edge is d -> c in f1 and c -> d in f2.
  auto put = [&](int slot, const Side& s) {
    tail_[slot] = s.tail;
    twin_[slot] = s.twin;
    twin_[s.twin] = slot;
    length_[slot] = s.length;
    signpost_[slot] = s.signpost;
  };
  put(3 * f1 + 0, sh2);
  put(3 * f1 + 1, st1);
  put(3 * f2 + 0, st2);
  put(3 * f2 + 1, sh1);
  const int dc = 3 * f1 + 2, cdh = 3 * f2 + 2;
  tail_[dc] = d;
  tail_[cdh] = c;
  twin_[dc] = cdh;
  twin_[cdh] = dc;
  length_[dc] = length_[cdh] = cd;
  // Around c the new edge lies between c -> a and c -> b, at f1's angle at c past c -> a.
  signpost_[cdh] = std::fmod(signpost_[3 * f1 + 0] + cornerAngle(3 * f1 + 0), coneAngle_[c]);
  signpost_[dc] = std::fmod(signpost_[3 * f2 + 0] + cornerAngle(3 * f2 + 0), coneAngle_[d]);
  vertexHalfedge_[a] = 3 * f1 + 1;
  vertexHalfedge_[b] = 3 * f2 + 1;
  vertexHalfedge_[c] = 3 * f1 + 0;
  vertexHalfedge_[d] = 3 * f2 + 0;
}

bool IntrinsicTriangulation::removeFlatVertex(int v) {
  for (;;) {
    const std::vector<int> around = outgoing(v);
    if (around.size() <= 3) break;
    auto flippableEdge =
        std::find_if(around.begin(), around.end(), [&](int h) { return flippable(h); });
    if (flippableEdge == around.end()) return false;
    flip(*flippableEdge);
  }
  const std::vector<int> around = outgoing(v);
  if (around.size() != 3) return false;
  int outer[3];
  for (int k = 0; k < 3; ++k) outer[k] = next(around[k]);
  const int keep = around[0] / 3;
  for (int o : outer) {
    const int f = twin_[o] / 3;
    if (f == around[0] / 3 || f == around[1] / 3 || f == around[2] / 3) return false;
  }
  struct Side {
    int tail, twin;
    double length, signpost;
  };
  Side sides[3];
  for (int k = 0; k < 3; ++k)
    sides[k] = {tail_[outer[k]], twin_[outer[k]], length_[outer[k]], signpost_[outer[k]]};
  for (int k = 1; k < 3; ++k)
    for (int c = 0; c < 3; ++c) tail_[3 * (around[k] / 3) + c] = -1;
  for (int k = 0; k < 3; ++k) {
    const int slot = 3 * keep + k;
    tail_[slot] = sides[k].tail;
    twin_[slot] = sides[k].twin;
    twin_[sides[k].twin] = slot;
    length_[slot] = sides[k].length;
    signpost_[slot] = sides[k].signpost;
    vertexHalfedge_[sides[k].tail] = slot;
  }
  vertexHalfedge_[v] = -1;
  return true;
}

std::vector<int> IntrinsicTriangulation::compact() {
  std::vector<int> vertexMap(coneAngle_.size(), -1);
  std::vector<double> cones;
  for (std::size_t v = 0; v < coneAngle_.size(); ++v)
    if (vertexHalfedge_[v] >= 0) {
      vertexMap[v] = int(cones.size());
      cones.push_back(coneAngle_[v]);
    }
  std::vector<int> halfedgeMap(tail_.size(), -1);
  int faces = 0;
  for (int f = 0; f < faceCount(); ++f)
    if (faceAlive(f)) {
      for (int c = 0; c < 3; ++c) halfedgeMap[3 * f + c] = 3 * faces + c;
      ++faces;
    }
  std::vector<int> tail(3 * faces), twin(3 * faces), vertexHalfedge(cones.size());
  std::vector<double> length(3 * faces), signpost(3 * faces);
  for (std::size_t h = 0; h < tail_.size(); ++h) {
    const int g = halfedgeMap[h];
    if (g < 0) continue;
    tail[g] = vertexMap[tail_[h]];
    twin[g] = halfedgeMap[twin_[h]];
    length[g] = length_[h];
    signpost[g] = signpost_[h];
    vertexHalfedge[tail[g]] = g;
  }
  tail_ = std::move(tail);
  twin_ = std::move(twin);
  length_ = std::move(length);
  signpost_ = std::move(signpost);
  coneAngle_ = std::move(cones);
  vertexHalfedge_ = std::move(vertexHalfedge);
  return vertexMap;
}

int IntrinsicTriangulation::makeDelaunay() {
  std::deque<int> queue;
  for (int h = 0; h < halfedgeCount(); ++h)
    if (faceAlive(h / 3) && h < twin_[h]) queue.push_back(h);
  int flips = 0;
  // Each flip lowers the Dirichlet energy, so the loop ends; the bound only guards bad input.
  const long bound = 100L * halfedgeCount() + 1000;
  while (!queue.empty() && flips < bound) {
    const int h = queue.front();
    queue.pop_front();
    const double opposite = cornerAngle(prev(h)) + cornerAngle(prev(twin_[h]));
    if (opposite <= kPi * (1.0 + 1e-12) || !flippable(h)) continue;
    const int faces[2] = {h / 3, twin_[h] / 3};  // the flip keeps the two faces' indices
    flip(h);
    ++flips;
    for (int f : faces)
      for (int c = 0; c < 3; ++c) queue.push_back(3 * f + c);
  }
  return flips;
}

SurfacePoint IntrinsicTriangulation::trace(int v, double direction, double distance) const {
  const double cone = coneAngle_[v];
  // The wedge of the face whose corner at v contains the direction.
  int start = -1;
  double offset = 0.0, best = 1e300;
  for (int h : outgoing(v)) {
    double psi = std::fmod(direction - signpost_[h], cone);
    if (psi < 0) psi += cone;
    const double beyond = psi - cornerAngle(h);
    // psi past the wedge by a rounding error still belongs to it; otherwise take the nearest.
    const double miss = beyond <= 0 ? 0.0 : beyond;
    if (miss < best) {
      best = miss;
      start = h;
      offset = std::min(psi, cornerAngle(h));
    }
  }
  SurfacePoint out;
  if (start < 0) return out;
  Eigen::Vector2d P[3];
  int corner0 = start % 3;
  int f = start / 3;
  P[corner0] = Eigen::Vector2d(0, 0);
  P[(corner0 + 1) % 3] = Eigen::Vector2d(length_[start], 0);
  P[(corner0 + 2) % 3] =
      thirdCorner(P[corner0], P[(corner0 + 1) % 3], length_[next(start)], length_[prev(start)]);
  const Eigen::Vector2d u(std::cos(offset), std::sin(offset));
  const Eigen::Vector2d target = distance * u;
  int entry = -1;  // the halfedge of f the ray came in through (-1: it starts at v)
  const int bound = 4 * faceCount() + 16;
  for (int step = 0; step < bound; ++step) {
    const Eigen::Vector3d b = barycentric(P, target);
    // Inside up to rounding relative to the triangle's size.
    if (b.minCoeff() >= -1e-12) {
      out.face = f;
      out.bary = b.cwiseMax(0.0) / b.cwiseMax(0.0).sum();
      return out;
    }
    int exit;
    if (entry < 0) {
      exit = next(start);
    } else {
      const Eigen::Vector2d C = P[(entry % 3 + 2) % 3];
      exit = cross(u, C) > 0 ? next(entry) : prev(entry);
    }
    // Cross into the neighbour: its entry runs the other way along the exit edge.
    const int tw = twin_[exit];
    const Eigen::Vector2d from = P[(exit % 3 + 1) % 3], to = P[exit % 3];
    f = tw / 3;
    const int ct = tw % 3;
    P[ct] = from;
    P[(ct + 1) % 3] = to;
    P[(ct + 2) % 3] = thirdCorner(from, to, length_[next(tw)], length_[prev(tw)]);
    entry = tw;
  }
  return out;
}

}  // namespace dform::exact
