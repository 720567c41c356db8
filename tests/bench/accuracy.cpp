// SPDX-License-Identifier: GPL-3.0-or-later
// The curve of distance from the exact D-Form against solve time that docs/benchmarks.md records:
// the paper model on the ellipse pair at each 3D smoothing weight w_3D, measured by the figure the
// gate's exact_distance_rel check judges (metrics.h: the 3D seam against the exact D-Form's
// after rigid alignment, over the seam's bounding-box diagonal).
#include "accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dform/pipeline/forward_pipeline.h"
#include "median.h"
#include "plot.h"

namespace {

using namespace dform;

// The accuracy goal: within 5e-5 of the seam's bounding-box diagonal in at most 0.3 s.
const double goalDistance = 5e-5, goalSeconds = 0.3;

struct Point {
  double weight = 0, solveSeconds = 0, rms = 0, max = 0;
};

// Distance (log scale) against solve time: the RMS, each point labelled with its weight, and the
// largest distance.
bool writeAccuracyPlot(const std::string& path, const std::vector<Point>& points) {
  double slowest = goalSeconds, nearest = goalDistance, farthest = goalDistance;
  for (const Point& p : points)
    slowest = std::max(slowest, p.solveSeconds), nearest = std::min(nearest, p.rms),
    farthest = std::max(farthest, p.max);
  PlotPanel panel{"Distance from the exact D-Form",
                  {"solve s (median)", std::ceil(2 * slowest) / 2, 0, ""},
                  {"distance / seam diagonal", std::pow(10.0, std::ceil(std::log10(farthest))),
                   std::pow(10.0, std::floor(std::log10(nearest))), ""},
                  {},
                  goalSeconds,
                  goalDistance};
  PlotSeries rms{"#1f77b4", "RMS (labels: w_3D)", {}, {}, {}},
      max{"#ff7f0e", "largest", {}, {}, {}};
  for (const Point& p : points) {
    char label[32];
    std::snprintf(label, sizeof label, "%g", p.weight);
    rms.x.push_back(p.solveSeconds), rms.y.push_back(p.rms), rms.labels.push_back(label);
    max.x.push_back(p.solveSeconds), max.y.push_back(p.max);
  }
  panel.series = {rms, max};
  return writePlot(path, {panel});
}

}  // namespace

int runAccuracy(int repeats, const std::string& plotPath, bool smoke) {
  // Resolution 75 meshes the pair with about 1k vertices (both pieces), the bar's size. The sweep
  // brackets the default w_3D, 0.01: below it the sheet bends more freely, nearer the exact shape.
  const std::vector<double> weights =
      smoke ? std::vector<double>{0.01}
            : std::vector<double>{0.03, 0.01, 0.003, 0.001, 0.0005, 0.0003, 0.0001};
  ForwardJob job;
  job.pieceA = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-a.svg";
  job.pieceB = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-b.svg";
  job.resolution = smoke ? 30 : 75;
  job.model = ModelChoice::Paper;
  std::printf(
      "| w_3D | vertices | solve s | LM iters | factorisations | exact distance (RMS) | "
      "exact distance (max) | L_error %% | L_max %% | flipped |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Point> points;
  for (const double weight : weights) {
    job.weights.smooth3d = weight;
    std::vector<double> solveSeconds;
    ForwardRun last;
    for (int r = 0; r < repeats; ++r) {
      MessageSink sink;
      Result<ForwardRun> run = runForward(job, sink);
      if (!run.isOk()) {
        std::fprintf(stderr, "dform_bench: w_3D %g: %s\n", weight, run.status().message().c_str());
        return 1;
      }
      last = std::move(run).value();
      solveSeconds.push_back(last.timings.solve);
    }
    const Metrics& m = last.metrics;
    if (std::isnan(m.exactDistanceRmsRel)) {
      std::fprintf(stderr, "dform_bench: no exact D-Form to compare with: %s\n",
                   m.exactNote.c_str());
      return 1;
    }
    points.push_back({weight, median(solveSeconds), m.exactDistanceRmsRel, m.exactDistanceMaxRel});
    std::printf("| %g | %ld | %.3f | %zu | %d | %.1e | %.1e | %.3f | %.3f | %d |\n", weight,
                long(last.model.a.flat.rows() + last.model.b.flat.rows()),
                points.back().solveSeconds, last.summary.iterations.size(),
                last.summary.factorisations, m.exactDistanceRmsRel, m.exactDistanceMaxRel,
                100 * m.lengthError, 100 * m.lengthErrorMax, m.flipped2d + m.flipped3d);
    std::fflush(stdout);
  }
  if (!plotPath.empty() && !writeAccuracyPlot(plotPath, points)) {
    std::fprintf(stderr, "dform_bench: cannot write %s\n", plotPath.c_str());
    return 1;
  }
  return 0;
}
