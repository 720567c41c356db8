// SPDX-License-Identifier: GPL-3.0-or-later
// A solved D-Form on disk: one OBJ per piece and per form (flat and 3D), each holding the seam as
// an `l` polyline in seam order (group `seam`), then the free boundary loops (group `boundary`)
// and the creases (group `crease`), so a saved result can be exported or validated again.
#pragma once

#include <map>
#include <string>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// File names inside a result folder.
struct ModelFileNames {
  static constexpr const char* aFlat = "piece-a-flat.obj";        ///< piece A as it is cut
  static constexpr const char* a3d = "piece-a-3d.obj";            ///< piece A bent in 3D
  static constexpr const char* bFlat = "piece-b-flat.obj";        ///< piece B as it is cut
  static constexpr const char* b3d = "piece-b-3d.obj";            ///< piece B bent in 3D
  static constexpr const char* targetCurve = "target-curve.obj";  ///< inverse results only
};

/// The SHA-256 of each file written or read, by its name in the folder (ModelFileNames).
using FileHashes = std::map<std::string, std::string>;

/// Which of a piece's two embeddings an OBJ file holds: the flat layout (z = 0) or the 3D shape.
enum class PieceForm { Flat, Shape3D };

/// Writes one piece as an OBJ file at `path`, atomically: its vertices in `form` (mm), its
/// triangles, then its seam, free boundary loops and creases as `l` polylines in groups `seam`,
/// `boundary` and `crease`. OutputFailed naming the file when it cannot be written. `sha256`, when
/// given, gets the SHA-256 of the bytes written.
Status writeObj(const std::string& path, const Piece& piece, PieceForm form,
                std::string* sha256 = nullptr);

/// Writes the four OBJ files of ModelFileNames into `dir` (which must exist) with writeObj;
/// `hashes`, when given, gets each one's SHA-256.
Status writeModel(const std::string& dir, const DForm& model, FileHashes* hashes = nullptr);

/// Writes an inverse result's target seam curve into `dir` as a closed OBJ polyline (atomically),
/// so that `dform validate` can measure D_error again; readCurve reads it back. `hashes`, when
/// given, gets its SHA-256.
Status writeTargetCurve(const std::string& dir, const Curve3& curve, FileHashes* hashes = nullptr);

/// Reads the four OBJ files back; checks that flat and 3D meshes of a piece agree in faces, seam,
/// free boundaries and creases, that each free boundary is a boundary loop of the mesh with the
/// piece on its left, that each crease runs along interior mesh edges from boundary to boundary,
/// and that the two seams have the same length (vertex count). An old file with one ungrouped
/// `l` reads as a seam with no free boundaries or creases. `hashes`, when given, gets the SHA-256
/// of the bytes each file read held.
Result<DForm> readModel(const std::string& dir, FileHashes* hashes = nullptr);

}  // namespace dform
