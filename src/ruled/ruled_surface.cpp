// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/ruled_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>

namespace dform::ruled {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

PieceTriangulation::PieceTriangulation(Points2 flat, const Faces& faces,
                                       const std::vector<std::pair<int, int>>& fixed)
    : flat_(std::move(flat)) {
  const int nF = int(faces.rows());
  tail_.resize(std::size_t(3 * nF));
  twin_.assign(std::size_t(3 * nF), -1);
  fixed_.assign(std::size_t(3 * nF), false);
  std::map<std::pair<int, int>, int> byEnds;
  for (int f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) {
      const int h = 3 * f + c;
      tail_[std::size_t(h)] = faces(f, c);
      byEnds[{faces(f, c), faces(f, (c + 1) % 3)}] = h;
    }
  for (const auto& [ends, h] : byEnds)
    if (const auto it = byEnds.find({ends.second, ends.first}); it != byEnds.end())
      twin_[std::size_t(h)] = it->second;
  for (const auto& [a, b] : fixed)
    for (const std::pair<int, int>& ends : {std::pair{a, b}, std::pair{b, a}})
      if (const auto it = byEnds.find(ends); it != byEnds.end())
        fixed_[std::size_t(it->second)] = true;
}

double PieceTriangulation::length(int h) const {
  return (flat_.row(head(h)) - flat_.row(tail(h))).norm();
}

double PieceTriangulation::area(int f) const {
  const Eigen::Vector2d a = flat_.row(tail_[std::size_t(3 * f)]),
                        b = flat_.row(tail_[std::size_t(3 * f + 1)]),
                        c = flat_.row(tail_[std::size_t(3 * f + 2)]);
  return 0.5 * cross2(b - a, c - a);
}

Faces PieceTriangulation::faces() const {
  Faces F(faceCount(), 3);
  for (int f = 0; f < faceCount(); ++f)
    for (int c = 0; c < 3; ++c) F(f, c) = tail_[std::size_t(3 * f + c)];
  return F;
}

bool PieceTriangulation::flippable(int h, double minTurn) const {
  const int t = twin(h);
  if (t < 0 || fixed(h)) return false;
  // The quadrilateral i, l, j, k counter-clockwise: k faces h, l faces its twin.
  const int i = tail(h), j = head(h), k = opposite(h), l = opposite(t);
  if (k == l) return false;
  const int corners[4] = {i, l, j, k};
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector2d p = flat_.row(corners[(c + 3) % 4]), q = flat_.row(corners[c]),
                          r = flat_.row(corners[(c + 1) % 4]);
    const Eigen::Vector2d u = q - p, w = r - q;
    // Turning left at every corner by more than minTurn: sin of the turn times both lengths.
    if (!(cross2(u, w) > std::sin(minTurn) * u.norm() * w.norm())) return false;
  }
  return true;
}

int PieceTriangulation::flip(int h) {
  assert(flippable(h, 0.0) && "flip of an edge that cannot be flipped");
  const int t = twin(h);
  const int f1 = h / 3, f2 = t / 3;
  const int i = tail(h), j = head(h), k = opposite(h), l = opposite(t);
  // Outer sides with their twins: j->k and k->i in f1, i->l and l->j in f2.
  const int jk = next(h), ki = prev(h), il = next(t), lj = prev(t);
  const int twins[4] = {twin(jk), twin(ki), twin(il), twin(lj)};
  const bool fixes[4] = {fixed(jk), fixed(ki), fixed(il), fixed(lj)};
  // New faces, the new edge first in each: f1 = (l, k, i) keeps k->i and takes i->l from f2;
  // f2 = (k, l, j) keeps l->j and takes j->k from f1.
  auto set = [&](int slot, int tailVertex, int twinSlot, bool isFixed) {
    tail_[std::size_t(slot)] = tailVertex;
    twin_[std::size_t(slot)] = twinSlot;
    fixed_[std::size_t(slot)] = isFixed;
    if (twinSlot >= 0) twin_[std::size_t(twinSlot)] = slot;
  };
  set(3 * f1 + 0, l, 3 * f2 + 0, false);
  set(3 * f1 + 1, k, twins[1], fixes[1]);
  set(3 * f1 + 2, i, twins[2], fixes[2]);
  set(3 * f2 + 0, k, 3 * f1 + 0, false);
  set(3 * f2 + 1, l, twins[3], fixes[3]);
  set(3 * f2 + 2, j, twins[0], fixes[0]);
  return 3 * f1 + 0;
}

std::vector<SurfaceEdge> RuledSurface::edges() const {
  std::vector<SurfaceEdge> out;
  std::map<std::pair<int, int>, std::size_t> seam;  // boundary edges of A by their surface ends
  for (int p = 0; p < 2; ++p) {
    const PieceTriangulation& T = pieces[std::size_t(p)];
    const std::vector<int>& vertex = vertexOf[std::size_t(p)];
    for (int h = 0; h < T.halfedgeCount(); ++h) {
      const int t = T.twin(h);
      if (t >= 0 && t < h) continue;
      SurfaceEdge e;
      e.piece = p;
      e.halfedge = h;
      e.i = vertex[std::size_t(T.tail(h))];
      e.j = vertex[std::size_t(T.head(h))];
      e.length = T.length(h);
      if (t < 0) {
        e.kind = EdgeKind::Boundary;
        const auto key = std::minmax(e.i, e.j);
        if (const auto it = seam.find(key); it != seam.end()) {
          // The seam chord's other side: one edge, both sides' mean length.
          out[it->second].length = 0.5 * (out[it->second].length + e.length);
          continue;
        }
        if (p == 0) seam[key] = out.size();
      } else {
        e.kind = T.fixed(h) ? EdgeKind::Crease : EdgeKind::Chord;
        e.k = vertex[std::size_t(T.opposite(h))];
        e.l = vertex[std::size_t(T.opposite(t))];
        e.weight = 3.0 * e.length * e.length / (T.area(h / 3) + T.area(t / 3));
      }
      out.push_back(e);
    }
  }
  for (const Tie& tie : ties) {
    SurfaceEdge e;
    e.i = tie.i;
    e.j = tie.j;
    e.length = tie.length;
    e.kind = EdgeKind::Tie;
    e.halfedge = -1;
    out.push_back(e);
  }
  return out;
}

bool RuledSurface::hasDoubleEdge() const {
  std::vector<std::pair<int, int>> ends;
  for (const SurfaceEdge& e : edges()) ends.push_back(std::minmax(e.i, e.j));
  std::sort(ends.begin(), ends.end());
  return std::adjacent_find(ends.begin(), ends.end()) != ends.end();
}

double dihedral(const Eigen::Vector3d& xi, const Eigen::Vector3d& xj, const Eigen::Vector3d& xk,
                const Eigen::Vector3d& xl, Eigen::Matrix<double, 4, 3>* gradient) {
  // Faces (i, j, k) and (j, i, l), both counter-clockwise seen from outside.
  const Eigen::Vector3d e = xj - xi;
  const double len = e.norm();
  const Eigen::Vector3d n1 = e.cross(xk - xi), n2 = (xl - xi).cross(e);
  const double s1 = n1.squaredNorm(), s2 = n2.squaredNorm();
  const double angle = std::atan2(n1.cross(n2).dot(e) / len, n1.dot(n2));
  if (gradient) {
    // Bridson, Marino and Fedkiw 2003: the normals' moves at the opposite corners, spread over
    // the edge's ends by where those corners project onto it.
    const Eigen::Vector3d gk = -len * n1 / s1, gl = -len * n2 / s2;
    const double ak = (xk - xi).dot(e) / (len * len), al = (xl - xi).dot(e) / (len * len);
    gradient->row(2) = gk.transpose();
    gradient->row(3) = gl.transpose();
    gradient->row(0) = (-(1.0 - ak) * gk - (1.0 - al) * gl).transpose();
    gradient->row(1) = (-ak * gk - al * gl).transpose();
  }
  return angle;
}

double bendingEnergy(const RuledSurface& surface, const std::vector<SurfaceEdge>& edges) {
  double energy = 0.0;
  for (const SurfaceEdge& e : edges) {
    if (e.kind != EdgeKind::Chord) continue;
    const double theta =
        dihedral(surface.X.row(e.i), surface.X.row(e.j), surface.X.row(e.k), surface.X.row(e.l));
    energy += e.weight * theta * theta;
  }
  return energy;
}

double maxLengthError(const RuledSurface& surface, const std::vector<SurfaceEdge>& edges) {
  double worst = 0.0;
  for (const SurfaceEdge& e : edges) {
    const double d = (surface.X.row(e.i) - surface.X.row(e.j)).norm();
    worst = std::max(worst, std::abs(d - e.length) / e.length);
  }
  return worst;
}

}  // namespace dform::ruled
