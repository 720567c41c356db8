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
#include <fstream>
#include <string>
#include <vector>

#include "pipeline/forward_pipeline.h"
#include "pipeline/inverse_pipeline.h"

namespace {

using namespace dform;

struct Case {
  bool forward;
  int resolution;
};

struct Measured {
  long vertices = 0;
  double solveSeconds = 0, runSeconds = 0, wallSeconds = 0, peakMb = 0, lError = 0, lMax = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Runs the case in this process and writes "vertices solve run L_error L_max" to fd.
void runCase(const Case& c, int fd) {
  MessageSink sink;
  long vertices = 0;
  double solve = 0, run = 0, lError = 0, lMax = 0;
  auto take = [&](const auto& r) {  // a ForwardRun or an InverseRun
    if (!r.isOk()) _exit(1);
    vertices = long(r.value().model.a.flat.rows() + r.value().model.b.flat.rows());
    solve = r.value().timings.solve, run = r.value().timings.total;
    lError = r.value().metrics.L_error, lMax = r.value().metrics.L_max;
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
  const int n = std::snprintf(line, sizeof line, "%ld %.6f %.6f %.9g %.9g\n", vertices, solve, run, lError, lMax);
  if (write(fd, line, std::size_t(n)) != n) _exit(1);
}

bool measure(const Case& c, Measured& out) {
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
  for (ssize_t got; (got = read(fds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, std::size_t(got));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  if (wait4(child, &status, 0, &usage) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return false;
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.peakMb = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KB on Linux
  return std::sscanf(text.c_str(), "%ld %lf %lf %lf %lf", &out.vertices, &out.solveSeconds, &out.runSeconds,
                     &out.lError, &out.lMax) == 5;
}

// Two panels, seconds and MB against thousands of vertices, forward and inverse series.
void writePlot(const std::string& path, const std::vector<Case>& cases, const std::vector<Measured>& rows) {
  const double width = 380, height = 260, left = 60, top = 30, gap = 90;
  double maxV = 0, maxT = 20, maxM = 0;
  for (const Measured& m : rows) maxV = std::max(maxV, m.vertices / 1000.0), maxT = std::max(maxT, m.wallSeconds),
                                 maxM = std::max(maxM, m.peakMb);
  maxV = 20 * std::ceil(maxV / 20), maxT = 10 * std::ceil(maxT / 10), maxM = 500 * std::ceil(maxM / 500);
  std::ofstream svg(path);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << 2 * width + gap + 2 * left << "' height='"
      << height + 2 * top + 40 << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  auto panel = [&](double x0, const char* title, double maxY, auto value, double goal, const char* unit) {
    auto px = [&](double v) { return x0 + v / maxV * width; };
    auto py = [&](double y) { return top + height - y / maxY * height; };
    svg << "<text x='" << x0 + width / 2 << "' y='" << top - 10 << "' text-anchor='middle' font-weight='bold'>"
        << title << "</text>\n";
    for (int k = 0; k <= 5; ++k) {
      const double vx = maxV * k / 5, vy = maxY * k / 5;
      svg << "<line x1='" << px(vx) << "' y1='" << py(0) << "' x2='" << px(vx) << "' y2='" << py(maxY)
          << "' stroke='#eee'/><text x='" << px(vx) << "' y='" << py(0) + 16 << "' text-anchor='middle'>" << vx
          << "k</text>\n<line x1='" << px(0) << "' y1='" << py(vy) << "' x2='" << px(maxV) << "' y2='" << py(vy)
          << "' stroke='#eee'/><text x='" << px(0) - 6 << "' y='" << py(vy) + 4 << "' text-anchor='end'>" << vy
          << "</text>\n";
    }
    svg << "<text x='" << x0 + width / 2 << "' y='" << top + height + 34 << "' text-anchor='middle'>vertices</text>"
        << "<text x='" << x0 - 48 << "' y='" << top + height / 2 << "' transform='rotate(-90 " << x0 - 48 << " "
        << top + height / 2 << ")' text-anchor='middle'>" << unit << "</text>\n";
    if (goal > 0 && goal <= maxY)
      svg << "<line x1='" << px(0) << "' y1='" << py(goal) << "' x2='" << px(maxV) << "' y2='" << py(goal)
          << "' stroke='#c00' stroke-dasharray='6 4'/><text x='" << px(maxV) << "' y='" << py(goal) - 4
          << "' text-anchor='end' fill='#c00'>goal</text>\n";
    for (const bool forward : {true, false}) {
      const char* colour = forward ? "#1f77b4" : "#ff7f0e";
      std::string points;
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (cases[i].forward != forward) continue;
        const double x = px(rows[i].vertices / 1000.0), y = py(value(rows[i]));
        points += std::to_string(x) + "," + std::to_string(y) + " ";
        svg << "<circle cx='" << x << "' cy='" << y << "' r='3.5' fill='" << colour << "'/>\n";
      }
      svg << "<polyline points='" << points << "' fill='none' stroke='" << colour << "' stroke-width='2'/>\n";
    }
    svg << "<rect x='" << x0 << "' y='" << top << "' width='" << width << "' height='" << height
        << "' fill='none' stroke='#333'/>\n";
  };
  panel(left, "Wall time (median), s", maxT, [](const Measured& m) { return m.wallSeconds; }, 20, "seconds");
  panel(left + width + gap, "Peak memory, MB", maxM, [](const Measured& m) { return m.peakMb; }, 2048, "MB");
  svg << "<text x='" << left << "' y='" << top + height + 54 << "' fill='#1f77b4'>forward (two ellipses)</text>"
      << "<text x='" << left + 200 << "' y='" << top + height + 54 << "' fill='#ff7f0e'>inverse (saddle curve)</text>"
      << "\n</svg>\n";
}

}  // namespace

int runScale(int repeats, const std::string& plotPath) {
  // Resolutions for about 1k, 10k, 50k and 100k vertices (both pieces): the ellipses give
  // 0.17 n^2 vertices, the saddle 0.17 n^2 too.
  const std::vector<Case> cases = {{true, 75},  {true, 240},  {true, 530},  {true, 750},
                                   {false, 75}, {false, 240}, {false, 540}, {false, 760}};
  std::printf("| run | resolution | vertices | solve s | run s | process wall s | peak MB | L_error %% | L_max %% |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Measured> rows;
  for (const Case& c : cases) {
    std::vector<double> solve, run, wall, peak;
    Measured m;
    for (int r = 0; r < repeats; ++r) {
      if (!measure(c, m)) {
        std::fprintf(stderr, "dform_bench: the %s case at resolution %d failed\n", c.forward ? "forward" : "inverse",
                     c.resolution);
        return 1;
      }
      solve.push_back(m.solveSeconds), run.push_back(m.runSeconds), wall.push_back(m.wallSeconds),
          peak.push_back(m.peakMb);
    }
    m.solveSeconds = median(solve), m.runSeconds = median(run), m.wallSeconds = median(wall);
    m.peakMb = *std::max_element(peak.begin(), peak.end());
    std::printf("| %s | %d | %ld | %.2f | %.2f | %.2f | %.0f | %.4f | %.3f |\n", c.forward ? "forward" : "inverse",
                c.resolution, m.vertices, m.solveSeconds, m.runSeconds, m.wallSeconds, m.peakMb, 100 * m.lError,
                100 * m.lMax);
    std::fflush(stdout);
    rows.push_back(m);
  }
  if (!plotPath.empty()) writePlot(plotPath, cases, rows);
  return 0;
}
