// An orthographic picture of a solved D-Form: the camera, the faces of both pieces in painter's
// order with their Lambert shade, and the pieces' colours. The report draws it as SVG, the export
// as the assembly page; both draw the same picture.
#pragma once

#include <Eigen/Core>
#include <array>
#include <unordered_set>
#include <vector>

#include "dform/core/types.h"

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
/// y up) and their depths, mean depth and Lambert shade in [0.35, 1] (a light from the upper left,
/// both sides lit).
struct SeenFace {
  int piece = 0;
  int face = 0;
  std::array<Eigen::Vector2d, 3> corners;
  std::array<double, 3> cornerDepths{};
  double depth = 0;
  double shade = 1;
};

/// A picture needs no more faces than it can show, while at resolution 1500 the pieces have 420k
/// triangles (a 32 MB assembly.svg, a report.html of 184 MB, seconds of hidden-line tests): a
/// finer mesh is drawn on about this many faces, its vertices clustered on a grid (vertex
/// clustering, Rossignac and Borrel).
constexpr double kDrawnFaces = 20000;

/// The grid cell that leaves about kDrawnFaces of a mesh of `faces` faces on a surface of `area`
/// (mm, mm^2), or 0 where the mesh has no more faces than that (nothing to merge).
double drawingCell(double area, Eigen::Index faces);

/// Points (rows, 2D or 3D) merged on a grid of `cell` (0: each its own): each point's cluster
/// and each cluster's mean, clusters numbered by first appearance (the same on every machine).
struct PointClusters {
  std::vector<int> of;
  Eigen::MatrixXd mean;
  double cell = 0;
};
PointClusters clusterPoints(const Eigen::MatrixXd& points, double cell);

/// Both pieces' 3D vertices (A's, then B's) merged together as a picture draws them: on the
/// drawingCell of their area, so that the seam, where their vertices coincide, stays one.
PointClusters drawnShapeClusters(const DForm& model);

/// Which faces of a mesh drawn on clusters are drawn: not one whose corners merged, nor a second
/// on the same three clusters. Without merging (cell 0) every face is.
class ClusteredFaces {
 public:
  explicit ClusteredFaces(double cell) : merged_(cell > 0) {}
  bool draws(std::array<int, 3> clusters);

 private:
  struct Hash {
    size_t operator()(const std::array<int, 3>& c) const {
      return std::hash<long long>()((static_cast<long long>(c[0]) * 1000003 + c[1]) * 1000003 +
                                    c[2]);
    }
  };
  bool merged_;
  std::unordered_set<std::array<int, 3>, Hash> drawn_;  // membership only: no order is read
};

/// Both pieces' faces, far first (painter's order); on a closed surface only those turned towards
/// the viewer (the others are hidden behind them). A mesh of more than kDrawnFaces faces is drawn
/// on about that many, both pieces' vertices clustered together (one face per cluster triple;
/// `face` is a solved face it stands for).
std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera);

/// The same with the model's vertices already clustered (`drawn`, drawnShapeClusters(model)), for
/// a caller that draws one model from several views.
std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera,
                                    const PointClusters& drawn);

/// A piece's colour (red, green, blue in [0, 1]) at a shade: A warm, B cool.
Eigen::Vector3d shadedPieceColour(int piece, double shade);

}  // namespace dform
