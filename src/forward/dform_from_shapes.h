// A D-Form from two flat shapes (forward modelling end to end, in memory): the seam laid out on
// both pieces, then the exact D-Form where it applies, else the paper's optimisation coarse to
// fine. Measuring the result is validate's (pipeline/forward_pipeline.h makeDForm does both).
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/messages.h"
#include "core/status.h"
#include "core/types.h"
#include "forward/forward.h"
#include "model/inextensible.h"
#include "model/run_types.h"

namespace dform {

/// Where a piece's seam starts: an arc-length fraction from the outline's first point, or the
/// outline point nearest to a given point (mm, page frame, y up).
struct StartPoint {
  bool nearestToPoint = false;
  double fraction = 0.0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

/// Which boundary of a piece is zipped (paper section 6.4): its outline, as in a classic D-Form,
/// or its one hole. Two holes make an anti D-Form, an outline and a hole a demi D-Form; the other
/// boundary of an annulus-like piece stays free.
enum class JoinedBoundary { Outer, Inner };

const char* joinedBoundaryName(JoinedBoundary boundary);  ///< "outer" or "inner"

/// The term weights a job starts from: paper Table 1's for a classic D-Form; for anti and demi
/// D-Forms (a hole joined) the 3D smoothness weight is 0.001, Table 1's inverse-mode value. At
/// 0.01 their free brims stay stiff enough to strain the seam past the 3% bar (docs/variants.md).
ForwardWeights defaultWeights(JoinedBoundary a, JoinedBoundary b);

/// Reads "outer,inner" (A's joined boundary, then B's; "outer" or "inner" each) into the job;
/// false when the text is not of that form.
bool parseJoin(const std::string& text, JoinedBoundary& a, JoinedBoundary& b);

/// Which model makes the 3D shape: the exact D-Form (Alexandrov's convex body of the glued
/// pieces, src/exact), the paper's optimisation, or the general engine (the paper's shape relaxed
/// to a stationary point of a stiff sheet's bending and stretching energy, forward/inextensible.h);
/// `Auto` takes the exact one wherever it applies (two discs zipped along their outlines, no drawn
/// creases, a convex glued metric), else the paper's.
enum class ModelChoice { Auto, Exact, Paper, General };

const char* modelChoiceName(ModelChoice model);  ///< "auto", "exact", "paper" or "general"
bool parseModelChoice(const std::string& text, ModelChoice& model);

/// The range of ForwardSettings::interiorEdgeFactor: finer meshes cost more than they show, and
/// coarser ones leave the paper model too few triangles to bend.
constexpr double kMinInteriorEdgeFactor = 0.25, kMaxInteriorEdgeFactor = 8.0;

/// Everything a forward run needs besides the two pieces: the model, which boundaries are
/// zipped, the starting pair, the mesh and the solve.
struct ForwardSettings {
  ModelChoice model = ModelChoice::Auto;
  JoinedBoundary joinA = JoinedBoundary::Outer, joinB = JoinedBoundary::Outer;
  StartPoint startA, startB;  ///< the starting pair (paper Definition 3), on the joined boundaries
  int resolution = 100;       ///< seam vertices per piece
  bool flip = false;          ///< zip B turned over (its mirror image) instead
  bool fitPerimeter = false;  ///< scale B uniformly to A's perimeter
  double perimeterTolerance = 0.005;  ///< largest |pA - pB| / max(pA, pB) accepted as equal
  double interiorEdgeFactor = 1.0;    ///< interior edge length / seam edge length, in
                                      ///< [kMinInteriorEdgeFactor, kMaxInteriorEdgeFactor]
  bool coarseToFine = true;           ///< start from solutions at 1/3, 1/9, ... of the resolution
  ForwardOptions solve;
  InextensibleOptions inextensible;  ///< the general engine's (ModelChoice::General)
};

/// A solved forward job: the model, which model made it and how the solve went.
struct SolvedDForm {
  DForm model;
  ModelUsed modelUsed;
  LocalGlobalSummary relaxation;  ///< the local-global start of the solve
  SolverSummary summary;          ///< the Levenberg-Marquardt solve
  int constraintRounds = 0;       ///< multiplier rounds that closed the seam and fixed the outlines
  Timings timings;
  double perimeterA = 0, perimeterB = 0;          ///< the joined boundaries' lengths as read, mm
  std::string sha256A, sha256B;                   ///< SHA-256 of each input file's bytes as read
  double scaleB = 1.0;                            ///< applied by fitPerimeter
  double startFractionA = 0, startFractionB = 0;  ///< resolved starting pair
};

/// Checks a job's numbers before any work is done (Usage errors).
Status validateForwardJob(const ForwardSettings& job);

/// The D-Form of two shapes in memory (mm, counter-clockwise loops, as io's readShape gives them):
/// checked (lengths, joins, the memory the run needs), meshed and solved by the exact model or the
/// paper's. Messages and errors name a piece by its outline's `source` (a file path), else
/// "piece A" / "piece B". A failed allocation is an error with the resolution that fits.
Result<SolvedDForm> solveDForm(Shape2 a, Shape2 b, const ForwardSettings& settings,
                               MessageSink& sink, const RunHooks& hooks = {});

}  // namespace dform
