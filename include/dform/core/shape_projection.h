// SPDX-License-Identifier: GPL-3.0-or-later
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
  /// The camera turned by `azimuthDeg` about z, then tilted by `elevationDeg` (degrees).
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
  /// 0 for piece A, 1 for piece B.
  int piece = 0;
  /// The face's index in its piece (a solved face it stands for when clustered).
  int face = 0;
  /// The corners on the screen in mm: x right, y up.
  std::array<Eigen::Vector2d, 3> corners;
  /// Each corner's depth in mm, away from the viewer.
  std::array<double, 3> cornerDepths{};
  /// The mean of the corners' depths, the painter's sort key.
  double depth = 0;
  /// Lambert shade in [0.35, 1].
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
  /// Each point's cluster, by the point's row.
  std::vector<int> of;
  /// Each cluster's mean point, one row per cluster.
  Eigen::MatrixXd mean;
  /// The grid cell the points were merged on (0: none merged).
  double cell = 0;
};
/// The clusters of `points` on a grid of `cell` (mm; 0 keeps each point its own).
PointClusters clusterPoints(const Eigen::MatrixXd& points, double cell);

/// Both pieces' 3D vertices (A's, then B's) merged together as a picture draws them: on the
/// drawingCell of their area, so that the seam, where their vertices coincide, stays one.
PointClusters drawnShapeClusters(const DForm& model);

/// Which faces of a mesh drawn on clusters are drawn: not one whose corners merged, nor a second
/// on the same three clusters. Without merging (cell 0) every face is.
class ClusteredFaces {
 public:
  /// Faces drawn on clusters of the grid `cell` (0: unmerged, every face drawn).
  explicit ClusteredFaces(double cell) : merged_(cell > 0) {}
  /// Whether a face on these three clusters is drawn; remembers it, so a second face on the same
  /// clusters is not.
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
