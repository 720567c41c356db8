// SPDX-License-Identifier: GPL-3.0-or-later
// Benchmark of the forward pipeline and the exporter. For each case it runs the whole job
// `repeats` times and prints the median of each stage's wall time, the vertex count and the
// figures, as a Markdown table for docs/benchmarks.md. Method and machine: docs/benchmarks.md.
//
//   dform_bench [--repeats N] [--smoke] [--export]
//   dform_bench --scale [--repeats N] [--plot FILE.svg]      (scale.cpp)
//   dform_bench --accuracy [--repeats N] [--plot FILE.svg]   (accuracy.cpp)
//   dform_bench --starts [--repeats N]                       (starts.cpp)
//
// --export times only the export: each forward case is solved once and exported N times; then a
// long seam, two flat 2.5 m squares (a 10 m seam, synthetic: tests/validate/models.h).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "accuracy.h"
#include "dform/core/allocator.h"
#include "dform/export/exporter.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "dform/pipeline/job_file.h"
#include "median.h"
#include "models.h"
#include "scale.h"
#include "starts.h"

namespace {

using namespace dform;

// Two outlines of samples/forward/ with the default settings but B's starting fraction, or, when
// jobFile is set, one of its job files run as the sample runs (join, starting pair, weights).
struct Case {
  const char* name;
  const char* a;
  const char* b;
  int resolution;
  double startB;
  ModelChoice model = ModelChoice::Auto;  ///< auto: the exact model wherever it applies
  const char* jobFile = nullptr;
};

// A hard sample of the paper model: its job file at another resolution (the bar's mesh size).
Case sampleJob(const char* name, const char* jobFile, int resolution) {
  return {name, nullptr, nullptr, resolution, 0.0, ModelChoice::Paper, jobFile};
}

std::string sample(const char* name) { return std::string(DFORM_SAMPLES_DIR) + "/forward/" + name; }

// Wall and CPU time (s) of one exportAll with the laser profile on a sheet large enough for every
// case (all five files written into `dir`); negative times when the export fails (said on
// stderr). The export runs on one thread, so on a shared machine its CPU time is what its wall
// time would be without the neighbours' load.
struct ExportTime {
  double wall = -1, cpu = -1;
};
ExportTime timeExport(const DForm& model, const std::filesystem::path& dir, double sheetW = 2000,
                      double sheetH = 2000) {
  ExportOptions options;
  options.templatesDir = DFORM_TEMPLATES_DIR;
  options.sheetWidthMm = sheetW;
  options.sheetHeightMm = sheetH;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  Result<ExportSummary> exported = exportAll(model, options, dir.string());
  const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (exported.isOk()) return {wall, cpu};
  std::fprintf(stderr, "dform_bench: export: %s\n", exported.status().message().c_str());
  return {};
}

Result<ForwardRun> solveCase(const Case& c) {
  ForwardJob job;
  if (c.jobFile) {
    Result<Job> read = readJobFile(sample(c.jobFile));
    if (!read.isOk()) return read.status();
    job = std::get<ForwardJob>(read.value().run);
  } else {
    job.pieceA = sample(c.a);
    job.pieceB = sample(c.b);
    job.startB.fraction = c.startB;
  }
  job.resolution = c.resolution;
  job.model = c.model;
  MessageSink sink;
  return runForward(job, sink);
}

// A distance from the exact D-Form, or "n/a" where there is none to compare with (metrics.h).
std::string exactDistance(double relative) {
  if (std::isnan(relative)) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", relative);
  return text;
}

// Times `repeats` exports of `model` and prints its row; false when an export fails.
bool exportRow(const std::string& name, const std::string& seam, const DForm& model, int repeats,
               const std::filesystem::path& dir, double sheetW = 2000, double sheetH = 2000) {
  std::vector<double> ms, cpuMs;
  for (int r = 0; r < repeats; ++r) {
    const ExportTime t = timeExport(model, dir, sheetW, sheetH);
    if (t.wall < 0) return false;
    ms.push_back(1000 * t.wall);
    cpuMs.push_back(1000 * t.cpu);
  }
  std::printf("| %s | %s | %ld | %.1f | %.1f | %.1f | %.1f |\n", name.c_str(), seam.c_str(),
              long(model.a.F.rows() + model.b.F.rows()), median(ms),
              *std::min_element(ms.begin(), ms.end()), *std::max_element(ms.begin(), ms.end()),
              median(cpuMs));
  std::fflush(stdout);
  return true;
}

// The export alone: each case solved once, then exported `repeats` times; then the long seam.
int benchExport(const std::vector<Case>& cases, int repeats, const std::filesystem::path& dir) {
  std::printf("| case | seam n | triangles | export ms, median | min | max | CPU ms, median |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    Result<ForwardRun> run = solveCase(c);
    if (!run.isOk()) {
      std::fprintf(stderr, "dform_bench: %s\n", run.status().message().c_str());
      return 1;
    }
    if (!exportRow(c.name, std::to_string(c.resolution), run.value().model, repeats, dir)) return 1;
  }
  const double side = 2500;
  const Piece square = test::foldedSquare(50, side, {}, "A");
  const DForm longSeam{square, test::mirroredCopy(square, "B")};
  return exportRow("10 m seam: two 2.5 m squares", "200", longSeam, repeats, dir, 2 * side + 300,
                   side + 200)
             ? 0
             : 1;
}

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();  // as build/dform does
  int repeats = 7;
  bool smoke = false, exportOnly = false, scale = false, accuracy = false, starts = false;
  std::string plot;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--smoke")) {
      smoke = true;
      repeats = 1;
    } else if (!std::strcmp(argv[i], "--export")) {
      exportOnly = true;
    } else if (!std::strcmp(argv[i], "--scale")) {
      scale = true;
    } else if (!std::strcmp(argv[i], "--accuracy")) {
      accuracy = true;
    } else if (!std::strcmp(argv[i], "--starts")) {
      starts = true;
    } else if (!std::strcmp(argv[i], "--plot") && i + 1 < argc) {
      plot = argv[++i];
    } else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr,
                   "usage: dform_bench [--repeats N] [--smoke] [--export] | --scale [--repeats N] "
                   "[--plot FILE.svg]"
                   " | --accuracy [--repeats N] [--plot FILE.svg] | --starts [--repeats N]\n");
      return 2;
    }
  }
  if (scale) return runScale(repeats, plot);
  if (accuracy) return runAccuracy(repeats, plot, false);
  if (starts) return runStarts(repeats);
  std::vector<Case> cases = {
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 50, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 75, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 100, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 100, 0.0, ModelChoice::Paper},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 200, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 200, 0.0, ModelChoice::Paper},
      {"circle + square", "circle.svg", "square.svg", 100, 0.0, ModelChoice::Paper},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 125, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 150, 0.0},
      {"ellipse, quarter turn", "ellipses-a.svg", "ellipses-a.svg", 75, 0.25},
      {"circle + square", "circle.svg", "square.svg", 75, 0.0},
      {"circle + square", "circle.svg", "square.svg", 125, 0.0},
      {"non-convex", "nonconvex-a.svg", "nonconvex-b.svg", 75, 0.0},
      {"non-convex", "nonconvex-a.svg", "nonconvex-b.svg", 125, 0.0},
      // The paper model at ~1k vertices for the ellipses and ~2.6k for the hard samples, the sizes
      // whose solve times docs/benchmarks.md records.
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 75, 0.0, ModelChoice::Paper},
      sampleJob("circle + square, mid side", "circle-square-mid-side.json", 125),
      sampleJob("non-convex, shifted", "nonconvex-shifted.json", 125),
      sampleJob("squaricle", "squaricle.json", 125),
      sampleJob("demi", "demi.json", 79),
      sampleJob("anti", "anti.json", 63),
      // The general engine against the referee: on convex pairs the exact body is the answer.
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 100, 0.0, ModelChoice::General},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 200, 0.0, ModelChoice::General},
      {"circle + square", "circle.svg", "square.svg", 100, 0.0, ModelChoice::General},
      {"non-convex", "nonconvex-a.svg", "nonconvex-b.svg", 100, 0.0, ModelChoice::General},
  };
  if (smoke)  // a tiny sample job too, so that the job-file rows keep working
    cases = {{"ellipses", "ellipses-a.svg", "ellipses-b.svg", 30, 0.0},
             sampleJob("anti", "anti.json", 20)};

  // Per process: benches of other checkouts on the same machine use the temporary folder too.
  const auto exportDir =
      std::filesystem::temp_directory_path() / ("dform-bench-export-" + std::to_string(::getpid()));
  std::filesystem::create_directories(exportDir);
  if (exportOnly) {
    const int status = benchExport(cases, repeats, exportDir);
    std::filesystem::remove_all(exportDir);
    return status;
  }
  std::printf(
      "| case | model | seam n | vertices | mesh s | solve s | run s | export s | LM iters | "
      "factorisations | L_error %% | L_max %% | B_error | flipped | exact distance (RMS) | "
      "exact distance (max) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    std::vector<double> mesh, solveSeconds, total, exportSeconds;
    ForwardRun last;
    for (int r = 0; r < repeats; ++r) {
      Result<ForwardRun> run = solveCase(c);
      if (!run.isOk()) {
        std::fprintf(stderr, "dform_bench: %s\n", run.status().message().c_str());
        return 1;
      }
      last = std::move(run).value();
      mesh.push_back(last.timings.mesh);
      solveSeconds.push_back(last.timings.solve);
      total.push_back(last.timings.total);
      exportSeconds.push_back(timeExport(last.model, exportDir).wall);
      if (exportSeconds.back() < 0) return 1;
    }
    const Metrics& m = last.metrics;
    std::printf(
        "| %s | %s | %d | %ld | %.3f | %.3f | %.3f | %.3f | %zu | %d | %.3f | %.3f | %.1e | %d | "
        "%s | %s |\n",
        c.name, last.modelUsed.name.c_str(), c.resolution,
        long(last.model.a.flat.rows() + last.model.b.flat.rows()), median(mesh),
        median(solveSeconds), median(total), median(exportSeconds), last.summary.iterations.size(),
        last.summary.factorisations, 100 * m.lengthError, 100 * m.lengthErrorMax, m.seamError,
        m.flipped2d + m.flipped3d, exactDistance(m.exactDistanceRmsRel).c_str(),
        exactDistance(m.exactDistanceMaxRel).c_str());
    std::fflush(stdout);
  }
  std::filesystem::remove_all(exportDir);

  // Inverse modelling: the whole run (read, pre-D-Form, solve, figures) per seam curve.
  std::printf(
      "\n| curve | model | seam n | vertices | init s | solve s | run s | LM iters | "
      "factorisations | "
      "D_error | L_error %% | L_max %% | round trip (RMS) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const std::vector<std::pair<const char*, int>> curves =
      smoke ? std::vector<std::pair<const char*, int>>{{"tennis-ball.obj", 40}}
            : std::vector<std::pair<const char*, int>>{{"tennis-ball.obj", 100},
                                                       {"saddle.obj", 100},
                                                       {"pushed-in.obj", 100},
                                                       {"rotated.json", 100}};
  for (const auto& [curve, n] : curves) {
    InverseJob job;
    job.curve = std::string(DFORM_SAMPLES_DIR) + "/inverse/" + curve;
    job.resolution = n;
    std::vector<double> init, solve, total;
    InverseRun last;
    for (int r = 0; r < repeats; ++r) {
      MessageSink sink;
      Result<InverseRun> run = runInverse(job, sink);
      if (!run.isOk()) {
        std::fprintf(stderr, "dform_bench: %s\n", run.status().message().c_str());
        return 1;
      }
      last = std::move(run).value();
      init.push_back(last.timings.mesh);
      solve.push_back(last.timings.solve);
      total.push_back(last.timings.total);
    }
    std::printf(
        "| %s | %s | %d | %ld | %.3f | %.3f | %.3f | %zu | %d | %.1e | %.3f | %.3f | %.1e |\n",
        curve, last.modelUsed.name.c_str(), n,
        long(last.model.a.flat.rows() + last.model.b.flat.rows()), median(init), median(solve),
        median(total), last.summary.iterations.size(), last.summary.factorisations,
        last.curveMatch.curveError, 100 * last.metrics.lengthError,
        100 * last.metrics.lengthErrorMax, last.curveMatch.roundtripRmsRel);
    std::fflush(stdout);
  }
  if (smoke) {
    std::printf("\n");
    return runAccuracy(repeats, "", true);
  }
  return 0;
}
