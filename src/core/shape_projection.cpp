#include "core/shape_projection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace dform {

ShapeCamera::ShapeCamera(double azimuthDeg, double elevationDeg) {
  const double az = azimuthDeg * M_PI / 180.0, el = elevationDeg * M_PI / 180.0;
  R_ = (Eigen::AngleAxisd(el, Eigen::Vector3d::UnitX()) *
        Eigen::AngleAxisd(-az, Eigen::Vector3d::UnitZ()))
           .toRotationMatrix();
}

Eigen::Vector3d ShapeCamera::depthAxis() const { return R_.row(1).transpose(); }

Eigen::Vector3d ShapeCamera::screen(const Eigen::Vector3d& p) const {
  // Screen: x right, y up = rotated (x, z); depth = rotated y.
  const Eigen::Vector3d q = R_ * p;
  return {q.x(), q.z(), q.y()};
}

std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera) {
  const Eigen::Vector3d light = Eigen::Vector3d(-0.4, 0.5, 1.0).normalized();  // screen frame
  // A closed surface (no free boundary; faces wind outward) hides every face turned away from
  // the viewer behind one turned towards it: those need no drawing. An open one shows both sides.
  const bool closed = model.a.freeBoundaries.empty() && model.b.freeBoundaries.empty();
  const Eigen::Vector3d away = camera.depthAxis();
  std::vector<SeenFace> faces;
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& p = piece == 0 ? model.a : model.b;
    for (Eigen::Index f = 0; f < p.F.rows(); ++f) {
      const Eigen::Vector3d p0 = p.shape.row(p.F(f, 0)).transpose();
      const Eigen::Vector3d outward =
          (p.shape.row(p.F(f, 1)).transpose() - p0).cross(p.shape.row(p.F(f, 2)).transpose() - p0);
      if (closed && outward.dot(away) > 0) continue;
      Eigen::Vector3d s[3];
      for (int k = 0; k < 3; ++k) s[k] = camera.screen(p.shape.row(p.F(f, k)).transpose());
      SeenFace seen;
      seen.piece = piece;
      seen.face = int(f);
      for (int k = 0; k < 3; ++k) {
        seen.corners[size_t(k)] = s[k].head<2>();
        seen.cornerDepths[size_t(k)] = s[k].z();
      }
      seen.depth = (s[0].z() + s[1].z() + s[2].z()) / 3.0;
      const Eigen::Vector3d n = (s[1] - s[0]).cross(s[2] - s[0]);
      const double lit = n.norm() > 0 ? std::abs(n.normalized().dot(light)) : 0.0;
      seen.shade = 0.35 + 0.65 * lit;
      faces.push_back(seen);
    }
  }
  // Far (large depth) first; ties by piece and face, so the order is the same on every machine.
  std::sort(faces.begin(), faces.end(), [](const SeenFace& a, const SeenFace& b) {
    if (a.depth != b.depth) return a.depth > b.depth;
    return a.piece != b.piece ? a.piece < b.piece : a.face < b.face;
  });
  return faces;
}

Eigen::Vector3d shadedPieceColour(int piece, double shade) {
  return piece == 0 ? Eigen::Vector3d(0.98, 0.72, 0.45) * shade
                    : Eigen::Vector3d(0.50, 0.70, 0.95) * shade;
}

}  // namespace dform
