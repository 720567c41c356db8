// SPDX-License-Identifier: GPL-3.0-or-later
// The model report.html's interactive 3D view draws (templates/report/viewer.js), as JSON.
#pragma once

#include <string>
#include <vector>

#include "dform/core/types.h"
#include "dform/report/views.h"

namespace dform {

/// Both pieces as the view draws them: {"pieces": [{"name", "colour" (the piece's colour, red,
/// green, blue in [0, 1]), "position" (x, y, z per vertex, mm), "curvature" (0xRRGGBB per vertex:
/// curvatureColour of the mean defect of the vertices merged into it), "index" (three vertices
/// per triangle)}, ...], "seam": [x, y, z, ...] (A's seam in order), "ticks": [{"label", "at"}]}.
/// A mesh of more than kDrawnFaces faces is drawn on about that many (drawnShapeClusters).
/// Coordinates are rounded to a ten-thousandth of the shape's size: the page stays small.
std::string viewerModelJson(const DForm& model, const CurvatureMaps& maps,
                            const std::vector<SeamTick>& ticks);

}  // namespace dform
