// SPDX-License-Identifier: GPL-3.0-or-later
#include "synthetic.h"

#include <cmath>

namespace dform::test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

DForm ellipseCircleDForm(int sectors, int rings, double ax, double by, double height) {
  const int nv = 1 + rings * sectors;
  auto vid = [&](int ring, int j) {
    return 1 + (ring - 1) * sectors + ((j % sectors) + sectors) % sectors;
  };
  // Seam of A and its cumulative polygon arc length.
  std::vector<Eigen::Vector2d> seamA(static_cast<size_t>(sectors));
  for (int j = 0; j < sectors; ++j) {
    const double phi = 2 * kPi * j / sectors;
    seamA[size_t(j)] = {ax * std::cos(phi), by * std::sin(phi)};
  }
  std::vector<double> cum(size_t(sectors) + 1, 0.0);
  for (int j = 0; j < sectors; ++j)
    cum[size_t(j) + 1] =
        cum[size_t(j)] + (seamA[size_t((j + 1) % sectors)] - seamA[size_t(j)]).norm();
  const double L = cum.back();
  // B: a circle, clockwise, vertex j at the angle of A's arc-length fraction; radius such that
  // the polygon's perimeter is exactly L.
  double chordSum = 0;
  for (int j = 0; j < sectors; ++j)
    chordSum += 2 * std::sin(kPi * (cum[size_t(j) + 1] - cum[size_t(j)]) / L);
  const double r = L / chordSum;

  DForm d;
  d.a.name = "A";
  d.b.name = "B";
  for (Piece* p : {&d.a, &d.b}) {
    p->flat.resize(nv, 2);
    p->shape.resize(nv, 3);
    p->flat.row(0) << 0, 0;
  }
  d.a.shape.row(0) << 0, 0, height;
  d.b.shape.row(0) << 0, 0, -height;
  for (int k = 1; k <= rings; ++k) {
    const double rho = double(k) / rings;
    for (int j = 0; j < sectors; ++j) {
      const int v = vid(k, j);
      const double psi = -2 * kPi * cum[size_t(j)] / L;
      d.a.flat.row(v) = rho * seamA[size_t(j)].transpose();
      d.b.flat.row(v) << rho * r * std::cos(psi), rho * r * std::sin(psi);
      const double z = height * (1 - rho * rho);
      d.a.shape.row(v) << rho * seamA[size_t(j)].x(), rho * seamA[size_t(j)].y(), z;
      d.b.shape.row(v) << rho * seamA[size_t(j)].x(), rho * seamA[size_t(j)].y(), -z;
    }
  }
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j < sectors; ++j) faces.emplace_back(0, vid(1, j), vid(1, j + 1));
  for (int k = 1; k < rings; ++k)
    for (int j = 0; j < sectors; ++j) {
      faces.emplace_back(vid(k, j), vid(k + 1, j), vid(k + 1, j + 1));
      faces.emplace_back(vid(k, j), vid(k + 1, j + 1), vid(k, j + 1));
    }
  d.a.F.resize(Eigen::Index(faces.size()), 3);
  d.b.F.resize(Eigen::Index(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) {
    d.a.F.row(Eigen::Index(i)) = faces[i].transpose();
    d.b.F.row(Eigen::Index(i)) << faces[i][0], faces[i][2], faces[i][1];  // B's flat is mirrored
  }
  for (int j = 0; j < sectors; ++j) {
    d.a.seam.push_back(vid(rings, j));
    d.b.seam.push_back(vid(rings, j));
  }
  return d;
}

std::vector<double> fakeCurvature(const Piece& piece) {
  std::vector<double> k;
  const double h = piece.shape.col(2).cwiseAbs().maxCoeff();
  for (Eigen::Index v = 0; v < piece.shape.rows(); ++v)
    k.push_back(piece.shape(v, 2) / (h > 0 ? h : 1));
  return k;
}

}  // namespace dform::test
