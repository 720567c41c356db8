// SPDX-License-Identifier: GPL-3.0-or-later
// The ruled engine's states with vertices inside the pieces (internal to src/forward): the paper
// model's shape at a few coarse resolutions made exact (ruled::isometricMesh), ranked at one
// resolution and carried to the job's level by level, so that every resolution finds the same
// states in the same order (docs/ruled.md, "Vertices inside the pieces").
#pragma once

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/ruled/isometric_mesh.h"

namespace dform::forward_detail {

/// The seam resolutions whose paper model shapes start the states (each at most the job's); the
/// last is the ranking resolution. The paper model settles in one of two states of the non-convex
/// sample depending on its resolution (50 and 200 in one, 100 and 400 in the other: docs/ruled.md),
/// so one start is not enough.
constexpr std::array<int, 2> kIsometricStartResolutions{50, 100};

/// Two states whose seams lie within this fraction of the seam's diagonal of each other (largest
/// distance, after the best rigid motion, mirror images included) are one. Exact shapes of rigid
/// triangles with free inner vertices form a continuum: one state reached from two starts differs
/// by about its discretisation (the non-convex sample's answer at 100 and 200 seam points: 1.3e-3),
/// while distinct states lie far apart (the non-convex sample's two: 3.8e-2; demi's: 5.3e-2).
constexpr double kSameIsometricState = 5e-3;

/// What the states are made from: the job's own ways of solving and meshing.
struct IsometricLevels {
  /// The paper model's solved shape at this many seam points, on the job's mesh; its iterations
  /// go to the run's progress hooks only where `reportsProgress` (one start at a time does).
  std::function<Result<DForm>(int resolution, bool reportsProgress)> paperShape;
  /// Both pieces meshed at this many seam points with this interior edge (a multiple of the seam
  /// edge), their shapes empty.
  std::function<Result<std::array<Piece, 2>>(int resolution, double interiorEdgeFactor)> mesh;
  /// Whether the caller asked the run to stop.
  std::function<bool()> stop;
  /// Whether the starts, and the ways round a mesh that cannot be made exact at once, are made on
  /// threads of their own side by side; false: all on the caller's thread, one after another.
  /// Either way the same states, in the same order.
  bool sideBySide = true;
};

/// A state of the sheet at the job's resolution.
struct IsometricState {
  std::string start;              ///< its start, as reports name it
  ruled::IsometricMesh exact;     ///< the state: every edge as long in 3D as it is flat
  double interiorEdgeFactor = 0;  ///< the interior edge of its mesh (a multiple of the seam edge)
  int steps = 0;                  ///< Gauss-Newton steps over every level
  /// Its bending energy at the ranking resolution (the last start's), by which states are ordered
  double rankingEnergy = 0;
};

/// Every distinct state found, least bending at the ranking resolution first, and the starts
/// that gave none.
struct IsometricStates {
  std::vector<IsometricState> states;
  std::vector<std::pair<std::string, std::string>> failures;  ///< per failed start: name, why
};

/// The states at `resolution` seam points on meshes of `interiorEdgeFactor` (or twice it where
/// that fails). The paper model's shape at each start resolution is made exact and carried to the
/// ranking resolution (kIsometricStartResolutions.back(), or the job's where coarser), the starts
/// side by side: all but the last on threads of their own, the last on the caller's (so the
/// levels' functions are called from several threads at once); the distinct states are ordered
/// by their bending energy there and each is carried on to `resolution`. Carrying a state one level
/// (twice the one below, the target last) meshes both pieces afresh, starts them from the exact
/// state below (barycentric in its flat triangles, which are rigid, so the start stretches only
/// where a fine edge crosses a fold) and makes them exact again: at once, else by stages
/// (IsometricMeshOptions::stages), else on twice the interior edge and from there onto the given
/// one again (where that fails too, the state on twice it). States within `sameState` of each other
/// are one.
IsometricStates isometricStates(int resolution, double interiorEdgeFactor,
                                const IsometricLevels& levels,
                                double sameState = kSameIsometricState);

}  // namespace dform::forward_detail
