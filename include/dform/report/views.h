// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures of a D-Form drawn by dform itself, as SVG: the 3D shape from a viewpoint (shaded, or
// coloured by Gaussian curvature) and the flat pieces coloured by curvature. For report.html.
#pragma once

#include <string>

#include "dform/core/types.h"

namespace dform {

/// How a picture of the 3D shape is taken: the camera's angles (degrees), its width and its
/// colours.
struct View {
  double azimuthDeg = 30;    ///< rotation about the vertical (model z) axis
  double elevationDeg = 25;  ///< tilt towards the viewer
  double widthPx = 360;      ///< the picture's width; the height follows the shape
  bool curvature = false;    ///< colour by angle defect instead of shading
};

/// Both pieces' curvature maps (angle defect per vertex, radians) and the colour scale they share:
/// the largest |angle defect| away from the seam, and at least 1e-3 rad.
struct CurvatureMaps {
  Eigen::VectorXd piece[2];  ///< each piece's angle defect per vertex, radians (A, B)
  double scale = 1.0;        ///< the |defect| the colour scale saturates at, radians
};

/// The maps of `model`, measured once for every picture of a page.
CurvatureMaps curvatureMaps(const DForm& model);

/// The curvature colour (red, green, blue in [0, 1]) of a defect `t` times the scale: blue
/// (negative), white (0), red (positive), saturating at |t| = 1.
Eigen::Vector3d curvatureColour(double t);

/// The closed 3D shape (both pieces) in orthographic projection, painter's order, Lambert shading
/// (A warm, B cool) or a blue-white-red curvature scale; the seam and the creases (class 'crease
/// mountain' dash-dot, 'crease valley' dashed) drawn on top.
/// `maps`: the model's curvatureMaps when the caller has them (else measured here when needed).
std::string shapeSvg(const DForm& model, const View& view, const CurvatureMaps* maps = nullptr);

/// A fold of the body through a flat piece (report.json's model.folds): a straight line between
/// two points of the piece's seam, in its flat coordinates, mm.
struct FlatFold {
  int piece = 0;         ///< 0 for A, 1 for B
  Eigen::Vector2d from;  ///< one end, on the piece's seam (mm)
  Eigen::Vector2d to;    ///< the other end (mm)
  bool crease = false;   ///< a found crease rather than a gentle fold
};

/// Both flat pieces side by side at the same scale, coloured by their 3D curvature, every boundary
/// loop outlined (holes stay empty), the body's folds (if any) drawn faintly (class 'fold gentle'
/// or 'fold steep', a found crease stronger), the creases drawn as in shapeSvg.
std::string flatCurvatureSvg(const DForm& model, double widthPx,
                             const CurvatureMaps* maps = nullptr,
                             const std::vector<FlatFold>& folds = {});

/// The curvature scale used by both (radians of angle defect at full colour): curvatureMaps' scale.
double curvatureScale(const DForm& model);

}  // namespace dform
