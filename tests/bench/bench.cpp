// Benchmark of the forward pipeline and the exporter. For each case it runs the whole job
// `repeats` times and prints the median of each stage's wall time, the vertex count and the
// figures, as a Markdown table for docs/benchmarks.md. Method and machine: docs/benchmarks.md.
//
//   dform_bench [--repeats N] [--smoke]
//   dform_bench --scale [--repeats N] [--plot FILE.svg]   (scale.cpp)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/allocator.h"
#include "export/exporter.h"
#include "pipeline/forward_pipeline.h"
#include "pipeline/inverse_pipeline.h"
#include "scale.h"

namespace {

using namespace dform;

struct Case {
  const char* name;
  const char* a;
  const char* b;
  int resolution;
  double startB;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string sample(const char* name) { return std::string(DFORM_SAMPLES_DIR) + "/forward/" + name; }

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();  // as build/dform does
  int repeats = 7;
  bool smoke = false, scale = false;
  std::string plot;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--smoke")) {
      smoke = true;
      repeats = 1;
    } else if (!std::strcmp(argv[i], "--scale")) {
      scale = true;
    } else if (!std::strcmp(argv[i], "--plot") && i + 1 < argc) {
      plot = argv[++i];
    } else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: dform_bench [--repeats N] [--smoke] | --scale [--repeats N] [--plot FILE.svg]\n");
      return 2;
    }
  }
  if (scale) return runScale(repeats, plot);
  std::vector<Case> cases = {
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 50, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 75, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 100, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 125, 0.0},
      {"ellipses", "ellipses-a.svg", "ellipses-b.svg", 150, 0.0},
      {"ellipse, quarter turn", "ellipses-a.svg", "ellipses-a.svg", 75, 0.25},
      {"circle + square", "circle.svg", "square.svg", 75, 0.0},
      {"circle + square", "circle.svg", "square.svg", 125, 0.0},
      {"non-convex", "nonconvex-a.svg", "nonconvex-b.svg", 75, 0.0},
      {"non-convex", "nonconvex-a.svg", "nonconvex-b.svg", 125, 0.0},
  };
  if (smoke) cases = {{"ellipses", "ellipses-a.svg", "ellipses-b.svg", 30, 0.0}};

  std::printf("| case | seam n | vertices | mesh s | solve s | run s | export s | LM iters | "
              "factorisations | L_error %% | L_max %% | B_error |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const auto exportDir = std::filesystem::temp_directory_path() / "dform-bench-export";
  std::filesystem::create_directories(exportDir);
  for (const Case& c : cases) {
    ForwardJob job;
    job.pieceA = sample(c.a);
    job.pieceB = sample(c.b);
    job.resolution = c.resolution;
    job.startB.fraction = c.startB;
    std::vector<double> mesh, solve, total, exportSeconds;
    ForwardRun last;
    for (int r = 0; r < repeats; ++r) {
      MessageSink sink;
      Result<ForwardRun> run = runForward(job, sink);
      if (!run.isOk()) {
        std::fprintf(stderr, "dform_bench: %s\n", run.status().message().c_str());
        return 1;
      }
      last = std::move(run).value();
      mesh.push_back(last.timings.mesh);
      solve.push_back(last.timings.solve);
      total.push_back(last.timings.total);

      ExportOptions options;
      options.templatesDir = DFORM_TEMPLATES_DIR;
      options.sheetWidthMm = options.sheetHeightMm = 2000;
      const auto start = std::chrono::steady_clock::now();
      Result<ExportSummary> exported = exportAll(last.model, options, exportDir.string());
      exportSeconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (!exported.isOk()) {
        std::fprintf(stderr, "dform_bench: export: %s\n", exported.status().message().c_str());
        return 1;
      }
    }
    const Metrics& m = last.metrics;
    std::printf("| %s | %d | %ld | %.3f | %.3f | %.3f | %.3f | %zu | %d | %.3f | %.3f | %.1e |\n",
                c.name, c.resolution, long(last.model.a.flat.rows() + last.model.b.flat.rows()),
                median(mesh), median(solve), median(total), median(exportSeconds),
                last.summary.iterations.size(), last.summary.factorisations, 100 * m.L_error,
                100 * m.L_max, m.B_error);
    std::fflush(stdout);
  }
  std::filesystem::remove_all(exportDir);

  // Inverse modelling: the whole run (read, pre-D-Form, solve, figures) per seam curve.
  std::printf("\n| curve | seam n | vertices | init s | solve s | run s | LM iters | factorisations | "
              "D_error | L_error %% | L_max %% |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  const std::vector<std::pair<const char*, int>> curves =
      smoke ? std::vector<std::pair<const char*, int>>{{"tennis-ball.obj", 40}}
            : std::vector<std::pair<const char*, int>>{{"tennis-ball.obj", 100}, {"saddle.obj", 100},
                                                       {"pushed-in.obj", 100}, {"rotated.json", 100}};
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
    std::printf("| %s | %d | %ld | %.3f | %.3f | %.3f | %zu | %d | %.1e | %.3f | %.3f |\n", curve, n,
                long(last.model.a.flat.rows() + last.model.b.flat.rows()), median(init),
                median(solve), median(total), last.summary.iterations.size(),
                last.summary.factorisations, last.curveMatch.D_error, 100 * last.metrics.L_error,
                100 * last.metrics.L_max);
    std::fflush(stdout);
  }
  return 0;
}
