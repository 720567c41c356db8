// SPDX-License-Identifier: GPL-3.0-or-later
// How long the solve of the non-convex sample pair takes as B's start moves round its outline, as
// a drag in the studio moves it: with the model a job chooses (the ruled engine, from the paper
// model's start) and with the paper model alone. At a few starts the shape is about to change and
// the paper model's relaxation drifts along a soft mode for up to its 2000 steps; the studio's
// live preview has to stay fast at those starts too (docs/benchmarks.md, "Studio").
#include "starts.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "dform/forward/dform_from_shapes.h"
#include "dform/io/outline_reader.h"
#include "median.h"

namespace {

using namespace dform;

constexpr int kStarts = 40;

}  // namespace

int runStarts(int repeats) {
  const std::string forward = std::string(DFORM_SAMPLES_DIR) + "/forward/";
  Result<Shape2> a = readOutline(forward + "nonconvex-a.svg");
  Result<Shape2> b = readOutline(forward + "nonconvex-b.svg");
  if (!a.isOk() || !b.isOk()) {
    std::fprintf(stderr, "dform_bench: %s\n",
                 (a.isOk() ? b.status() : a.status()).message().c_str());
    return 1;
  }
  std::printf(
      "| model | seam points | median over %d starts | slowest start (B's) | its relaxation steps "
      "|\n|---|---|---|---|---|\n",
      kStarts);
  // The studio's live preview and its strip's cards, by the model a job chooses and the paper's.
  for (auto [model, resolution] : {std::pair{ModelChoice::Auto, 24},
                                   {ModelChoice::Auto, 36},
                                   {ModelChoice::Paper, 24},
                                   {ModelChoice::Paper, 36}}) {
    std::vector<double> seconds;
    double slowest = -1;
    int slowestStart = 0, slowestSteps = 0;
    for (int k = 0; k < kStarts; ++k) {
      ForwardSettings settings;
      settings.model = model;
      settings.resolution = resolution;
      settings.startB.fraction = double(k) / kStarts;
      std::vector<double> repeated;
      int steps = 0;
      for (int r = 0; r < repeats; ++r) {
        MessageSink sink;
        const auto began = std::chrono::steady_clock::now();
        Result<SolvedDForm> solved = solveDForm(a.value(), b.value(), settings, sink);
        repeated.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
        if (!solved.isOk()) {
          std::fprintf(stderr, "dform_bench: B's start %.3f: %s\n", settings.startB.fraction,
                       solved.status().message().c_str());
          return 1;
        }
        steps = solved.value().relaxation.iterations;
      }
      seconds.push_back(median(repeated));
      if (seconds.back() > slowest) {
        slowest = seconds.back();
        slowestStart = k;
        slowestSteps = steps;
      }
    }
    std::printf("| %s | %d | %.1f ms | %.1f ms (%.3f) | %s |\n", modelChoiceName(model), resolution,
                1e3 * median(seconds), 1e3 * slowest, double(slowestStart) / kStarts,
                model == ModelChoice::Paper ? std::to_string(slowestSteps).c_str() : "");
  }
  return 0;
}
