// SPDX-License-Identifier: GPL-3.0-or-later
// Scaling of forward and inverse runs with the mesh size: each case runs in a child process of
// its own, so that its peak memory (the child's maximum resident set, from wait4) and its wall
// time are its alone. Prints a Markdown table and writes an SVG plot of time and memory against
// vertices (docs/benchmarks.md, "Scale").
#include "scale.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "median.h"
#include "plot.h"

namespace {

using namespace dform;

struct ScaleCase {
  bool forward;
  int resolution;
};

struct Measured {
  long vertices = 0;
  double solveSeconds = 0, runSeconds = 0, wallSeconds = 0, peakMb = 0, lError = 0, lMax = 0;
};

// Runs the case in this process and writes "vertices solve run L_error L_max" to fd.
void runCase(const ScaleCase& c, int fd) {
  MessageSink sink;
  long vertices = 0;
  double solve = 0, run = 0, lError = 0, lMax = 0;
  auto take = [&](const auto& r) {  // a ForwardRun or an InverseRun
    if (!r.isOk()) _exit(1);
    vertices = long(r.value().model.a.flat.rows() + r.value().model.b.flat.rows());
    solve = r.value().timings.solve, run = r.value().timings.total;
    lError = r.value().metrics.lengthError, lMax = r.value().metrics.lengthErrorMax;
  };
  if (c.forward) {
    ForwardJob job;
    job.pieceA = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-a.svg";
    job.pieceB = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-b.svg";
    job.resolution = c.resolution;
    take(runForward(job, sink));
  } else {
    InverseJob job;
    job.curve = std::string(DFORM_SAMPLES_DIR) + "/inverse/saddle.obj";
    job.resolution = c.resolution;
    take(runInverse(job, sink));
  }
  char line[256];
  const int n = std::snprintf(line, sizeof line, "%ld %.6f %.6f %.9g %.9g\n", vertices, solve, run,
                              lError, lMax);
  if (write(fd, line, std::size_t(n)) != n) _exit(1);
}

bool measure(const ScaleCase& c, Measured& out) {
  int fds[2];
  if (pipe(fds) != 0) return false;
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child < 0) return false;
  if (child == 0) {
    close(fds[0]);
    runCase(c, fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buffer[256];
  for (ssize_t got; (got = read(fds[0], buffer, sizeof buffer)) > 0;)
    text.append(buffer, std::size_t(got));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  if (wait4(child, &status, 0, &usage) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return false;
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.peakMb = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KB on Linux
  return std::sscanf(text.c_str(), "%ld %lf %lf %lf %lf", &out.vertices, &out.solveSeconds,
                     &out.runSeconds, &out.lError, &out.lMax) == 5;
}

// Two panels, seconds and MB against thousands of vertices, forward and inverse series.
bool writeScalePlot(const std::string& path, const std::vector<ScaleCase>& cases,
                    const std::vector<Measured>& rows) {
  double maxV = 0, maxT = 20, maxM = 0;
  for (const Measured& m : rows)
    maxV = std::max(maxV, m.vertices / 1000.0), maxT = std::max(maxT, m.wallSeconds),
    maxM = std::max(maxM, m.peakMb);
  const PlotAxis vertices{"vertices", 20 * std::ceil(maxV / 20), 0, "k"};
  PlotPanel time{
      "Wall time (median), s", vertices, {"seconds", 10 * std::ceil(maxT / 10), 0, ""}, {}, 0, 20};
  PlotPanel memory{
      "Peak memory, MB", vertices, {"MB", 500 * std::ceil(maxM / 500), 0, ""}, {}, 0, 2048};
  for (const bool forward : {true, false}) {
    const std::string colour = forward ? "#1f77b4" : "#ff7f0e";
    PlotSeries wall{
        colour, forward ? "forward (two ellipses)" : "inverse (saddle curve)", {}, {}, {}};
    PlotSeries peak = wall;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (cases[i].forward != forward) continue;
      wall.x.push_back(rows[i].vertices / 1000.0), wall.y.push_back(rows[i].wallSeconds);
      peak.x.push_back(rows[i].vertices / 1000.0), peak.y.push_back(rows[i].peakMb);
    }
    time.series.push_back(wall), memory.series.push_back(peak);
  }
  return writePlot(path, {time, memory});
}

}  // namespace

int runScale(int repeats, const std::string& plotPath) {
  // Resolutions for about 1k, 10k, 50k and 100k vertices (both pieces): the ellipses give
  // 0.17 n^2 vertices, the saddle 0.17 n^2 too.
  const std::vector<ScaleCase> cases = {{true, 75},  {true, 240},  {true, 530},  {true, 750},
                                        {false, 75}, {false, 240}, {false, 540}, {false, 760}};
  std::printf(
      "| run | resolution | vertices | solve s | run s | process wall s | peak MB | L_error %% | "
      "L_max %% |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Measured> rows;
  for (const ScaleCase& c : cases) {
    std::vector<double> solve, run, wall, peak;
    Measured m;
    for (int r = 0; r < repeats; ++r) {
      if (!measure(c, m)) {
        std::fprintf(stderr, "dform_bench: the %s case at resolution %d failed\n",
                     c.forward ? "forward" : "inverse", c.resolution);
        return 1;
      }
      solve.push_back(m.solveSeconds), run.push_back(m.runSeconds), wall.push_back(m.wallSeconds),
          peak.push_back(m.peakMb);
    }
    m.solveSeconds = median(solve), m.runSeconds = median(run), m.wallSeconds = median(wall);
    m.peakMb = *std::max_element(peak.begin(), peak.end());
    std::printf("| %s | %d | %ld | %.2f | %.2f | %.2f | %.0f | %.4f | %.3f |\n",
                c.forward ? "forward" : "inverse", c.resolution, m.vertices, m.solveSeconds,
                m.runSeconds, m.wallSeconds, m.peakMb, 100 * m.lError, 100 * m.lMax);
    std::fflush(stdout);
    rows.push_back(m);
  }
  if (!plotPath.empty() && !writeScalePlot(plotPath, cases, rows)) {
    std::fprintf(stderr, "dform_bench: cannot write %s\n", plotPath.c_str());
    return 1;
  }
  return 0;
}
