// An orthographic picture of a solved D-Form: the camera, the faces of both pieces in painter's
// order with their Lambert shade, and the pieces' colours. The report draws it as SVG, the export
// as the assembly page; both draw the same picture.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/types.h"

namespace dform {

/// The camera: it turns about the model's vertical (z) axis by `azimuthDeg`, then tilts towards
/// the viewer by `elevationDeg`.
class ShapeCamera {
 public:
  ShapeCamera(double azimuthDeg, double elevationDeg);
  /// A model point on the screen: x right, y up, z the depth (away from the viewer).
  Eigen::Vector3d screen(const Eigen::Vector3d& p) const;
  /// The model direction that points away from the viewer (the screen's depth).
  Eigen::Vector3d depthAxis() const;

 private:
  Eigen::Matrix3d R_;
};

/// One triangle as seen: its piece (0 = A, 1 = B), face index, corners on the screen (x right,
/// y up) and their depths, mean depth and Lambert shade in [0.35, 1] (a light from the upper left, both sides lit).
struct SeenFace {
  int piece = 0;
  int face = 0;
  std::array<Eigen::Vector2d, 3> corners;
  std::array<double, 3> cornerDepths{};
  double depth = 0;
  double shade = 1;
};

/// Both pieces' faces, far first (painter's order); on a closed surface only those turned towards
/// the viewer (the others are hidden behind them).
std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera);

/// A piece's colour (red, green, blue in [0, 1]) at a shade: A warm, B cool.
Eigen::Vector3d shadedPieceColour(int piece, double shade);

}  // namespace dform
