// SPDX-License-Identifier: GPL-3.0-or-later
// The ruled engine in a forward run (internal to src/forward): the surface of rigid flat
// triangles built from the seam layout, solved from the paper model's shape (and its mirror
// image where the sheet has a free brim), the least bending state meshed as the run's model.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/forward/dform_from_shapes.h"
#include "seam_layout.h"

namespace dform::forward_detail {

/// Why the ruled engine is not tried on this job, or "" when it is: drawn creases must be
/// straight and the seam at most ruled::kMaxRuledSeam points; unless `asked`, a piece zipped along
/// its outline must not meet a seam point of negative curvature (two pieces' angles summing to
/// more than 360 degrees), where the engine finds no state or one folded back on itself
/// (docs/ruled.md, "Limits").
std::string ruledModelRefusal(const ForwardSettings& job, const SeamLayout& layout, bool asked);

/// The first seam point where the two pieces' angles sum to more than 360 degrees (after
/// equalising chords) and that sum, or -1 where the glued metric has none.
std::pair<int, double> negativelyCurvedSeamPoint(const ForwardSettings& job,
                                                 const SeamLayout& layout);

/// The ruled engine's start interior edges on a sheet with a free brim, as multiples of the seam
/// edge. There its start needs only the boundary points' places: on the anti sample the paper
/// model on meshes of 1 to 4 leads to one state (bending 28.288181410596, 128 flips), and 3 takes
/// a fifth of the time of 1; a mesh of 8 leads to another state (bending 30.60) the sheet can sit
/// in, so it is a second start. A closed sheet starts from the job's own mesh.
constexpr double kRuledStartInteriorEdge = 3.0;
constexpr double kRuledSecondStartInteriorEdge = 8.0;

/// A start's shape and the name reports give it.
struct NamedShape {
  std::string name;
  DForm model;
};

/// Replaces run.model (the paper model's solution of the same job, the first start) by the ruled
/// engine's least bending state and sets run.modelUsed; `otherStarts` are further shapes of the
/// same seam to start from (each, like the first, with its mirror image where the sheet has a free
/// brim). On failure (no state, or the least bending one folds a chord by more than
/// `largestFoldDeg`) leaves run as it is and returns SolveFailed saying why.
Status solveRuledModel(const ForwardSettings& job, const SeamLayout& layout, SolvedDForm& run,
                       const std::vector<NamedShape>& otherStarts, MessageSink& sink,
                       double largestFoldDeg);

}  // namespace dform::forward_detail
