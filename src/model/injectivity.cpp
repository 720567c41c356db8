// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/injectivity.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <utility>

#include "dform/core/interrupt.h"

namespace dform {

FoldGuard::FoldGuard(const VariableLayout& layout, const Piece& a, const Piece& b) {
  const Piece* pieces[2] = {&a, &b};
  for (int p = 0; p < 2; ++p) {
    const Piece& piece = *pieces[p];
    using Edge = std::pair<int, int>;
    auto key = [](int i, int j) { return Edge(std::min(i, j), std::max(i, j)); };
    std::map<Edge, bool> crease;
    for (const std::vector<int>& line : piece.creases)
      for (std::size_t k = 0; k + 1 < line.size(); ++k) crease[key(line[k], line[k + 1])] = true;
    std::map<Edge, int> firstFace;
    const int base = int(faces_.size());
    for (int f = 0; f < piece.F.rows(); ++f) {
      if (f % 4096 == 0) throwIfInterrupted("the solve");
      Face face;
      for (int c = 0; c < 3; ++c) {
        face.x[c] = layout.x(p, piece.F(f, c));
        face.u[c] = layout.u(p, piece.F(f, c));
      }
      faces_.push_back(face);
      for (int c = 0; c < 3; ++c) {
        const Edge e = key(piece.F(f, c), piece.F(f, (c + 1) % 3));
        if (crease.count(e)) continue;
        const auto [it, fresh] = firstFace.emplace(e, base + f);
        if (!fresh) neighbours_.push_back({it->second, base + f});
      }
    }
  }
}

// A step may not turn over what stood upright before it. Slivers are let be: a 3D triangle whose
// area is below 1e-3 of the sum of its squared edges (an equilateral one has 0.43) has a normal
// that a rounding turns round, so the sign alone would decide there, and one refusal would block
// every later step.
constexpr double kSliver = 1e-3;

FoldGuard::Orientations FoldGuard::orientations(const Eigen::VectorXd& x) const {
  Orientations out;
  out.value.assign(faces_.size() + neighbours_.size(), 0.0);
  out.clear.assign(out.value.size(), false);
  std::vector<Eigen::Vector3d> normal(faces_.size());
  std::vector<bool> wellShaped(faces_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Face& t = faces_[f];
    const Eigen::Vector2d u0 = x.segment<2>(t.u[0]), e1 = x.segment<2>(t.u[1]) - u0,
                          e2 = x.segment<2>(t.u[2]) - u0;
    out.value[f] = e1.x() * e2.y() - e1.y() * e2.x();
    out.clear[f] = out.value[f] > 0.0;
    const Eigen::Vector3d x0 = x.segment<3>(t.x[0]), d1 = x.segment<3>(t.x[1]) - x0,
                          d2 = x.segment<3>(t.x[2]) - x0;
    normal[f] = d1.cross(d2);
    wellShaped[f] = normal[f].norm() >=
                    kSliver * (d1.squaredNorm() + d2.squaredNorm() + (d2 - d1).squaredNorm());
  }
  for (std::size_t k = 0; k < neighbours_.size(); ++k) {
    const auto [f, g] = neighbours_[k];
    const double cosine = normal[f].dot(normal[g]);
    out.value[faces_.size() + k] = cosine;
    out.clear[faces_.size() + k] = wellShaped[f] && wellShaped[g] && cosine >= 0.0;
  }
  return out;
}

int FoldGuard::count(const Eigen::VectorXd& x) const {
  // validate's test: a flat triangle with area <= 0, a 3D pair with a negative dot product.
  const std::vector<double> value = orientations(x).value;
  int n = 0;
  for (std::size_t k = 0; k < value.size(); ++k)
    n += k < faces_.size() ? value[k] <= 0.0 : value[k] < 0.0;
  return n;
}

bool FoldGuard::addsFold(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const {
  const Orientations before = orientations(from), after = orientations(to);
  for (std::size_t k = 0; k < after.value.size(); ++k)
    if (before.clear[k] && (k < faces_.size() ? after.value[k] <= 0.0 : after.value[k] < 0.0))
      return true;
  return false;
}

void refuseNewFolds(const FoldGuard& guard, SolverOptions& solver) {
  solver.acceptStep = [&guard](const Eigen::VectorXd& from, const Eigen::VectorXd& to) {
    return !guard.addsFold(from, to);
  };
}

}  // namespace dform
