// The forward run end to end: two outline files in, a solved and measured D-Form out.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <string>

#include "core/messages.h"
#include "core/status.h"
#include "core/types.h"
#include "forward/forward.h"
#include "validate/metrics.h"

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

struct ForwardJob {
  std::string pieceA, pieceB;  ///< outline files (SVG or JSON points)
  JoinedBoundary joinA = JoinedBoundary::Outer, joinB = JoinedBoundary::Outer;
  StartPoint startA, startB;   ///< the starting pair (paper Definition 3), on the joined boundaries
  int resolution = 100;        ///< seam vertices per piece
  bool flip = false;           ///< zip B turned over (its mirror image) instead
  bool fitPerimeter = false;   ///< scale B uniformly to A's perimeter
  double perimeterTolerance = 0.005;  ///< largest |pA - pB| / max(pA, pB) accepted as equal
  double interiorEdgeFactor = 1.0;    ///< interior edge length / seam edge length
  bool coarseToFine = true;           ///< start from solutions at 1/3, 1/9, ... of the resolution
  ForwardOptions solve;
};

/// Seconds spent in each stage.
struct Timings {
  double read = 0, mesh = 0, solve = 0, total = 0;
};

struct ForwardRun {
  DForm model;
  Metrics metrics;
  LocalGlobalSummary relaxation;  ///< the local-global start of the solve
  SolverSummary summary;          ///< the Levenberg-Marquardt solve
  int constraintRounds = 0;       ///< multiplier rounds that closed the seam and fixed the outlines
  Timings timings;
  double perimeterA = 0, perimeterB = 0;  ///< the joined boundaries' lengths as read, mm
  std::string sha256A, sha256B;           ///< SHA-256 of each input file's bytes as read
  double scaleB = 1.0;                    ///< applied by fitPerimeter
  double startFractionA = 0, startFractionB = 0;  ///< resolved starting pair
};

/// Hooks for a caller that shows progress or can be interrupted.
struct RunHooks {
  /// Each iteration of a stage ("relaxing": local-global steps, "solving": Levenberg-Marquardt).
  std::function<void(const char* stage, const IterationSummary&)> onIteration;
  const std::atomic<bool>* interrupted = nullptr;  ///< checked between iterations
};

/// Reads, checks, meshes, solves and measures. Errors name the file and the problem.
Result<ForwardRun> runForward(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks = {});

/// Checks a job's numbers before any work is done (Usage errors).
Status validateForwardJob(const ForwardJob& job);

}  // namespace dform
