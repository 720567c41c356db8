// A solved D-Form on disk: one OBJ per piece and per form (flat and 3D), each holding the seam as
// an `l` polyline in seam order (group `seam`), then the free boundary loops (group `boundary`)
// and the creases (group `crease`), so a saved result can be exported or validated again.
#pragma once

#include <string>

#include "core/status.h"
#include "core/types.h"

namespace dform {

/// File names inside a result folder.
struct ModelFileNames {
  static constexpr const char* aFlat = "piece-a-flat.obj";
  static constexpr const char* a3d = "piece-a-3d.obj";
  static constexpr const char* bFlat = "piece-b-flat.obj";
  static constexpr const char* b3d = "piece-b-3d.obj";
  static constexpr const char* targetCurve = "target-curve.obj";  ///< inverse results only
};

/// Writes the four OBJ files into `dir` (which must exist), each atomically.
Status writeModel(const std::string& dir, const DForm& model);

/// Writes an inverse result's target seam curve into `dir` as a closed OBJ polyline (atomically),
/// so that `dform validate` can measure D_error again; readCurve reads it back.
Status writeTargetCurve(const std::string& dir, const Curve3& curve);

/// Reads the four OBJ files back; checks that flat and 3D meshes of a piece agree in faces, seam,
/// free boundaries and creases, that each free boundary is a boundary loop of the mesh with the
/// piece on its left, that each crease runs along interior mesh edges from boundary to boundary,
/// and that the two seams have the same length (vertex count). An old file with one ungrouped
/// `l` reads as a seam with no free boundaries or creases.
Result<DForm> readModel(const std::string& dir);

}  // namespace dform
