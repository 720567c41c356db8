// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/resources.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "dform/core/constants.h"
#include "dform/model/run_control.h"

namespace dform {

namespace {

// A number from a /proc or /sys file; -1 when absent or not a number ("max").
double readNumber(const std::string& path, const std::string& key = "") {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!key.empty() && line.rfind(key, 0) != 0) continue;
    std::istringstream fields(key.empty() ? line : line.substr(key.size()));
    double value = -1.0;
    if (fields >> value) return value;
    return -1.0;
  }
  return -1.0;
}

constexpr double kProgramBytes = 64.0 * (1 << 20);
constexpr double kBytesPerVertexDirect = 36.0 * 1024;  // measured: 690 MB at 19k vertices
constexpr double kBytesPerVertexRelaxed = 9.0 * 1024;  // measured: 790 MB at 97k vertices
constexpr double kUsableFraction = 0.8;

// This process's cgroup folder (cgroup v2: the "0::/path" line of /proc/self/cgroup).
std::string cgroupFolder() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("0::", 0) == 0) return "/sys/fs/cgroup" + line.substr(3);
  return "/sys/fs/cgroup";
}

// Waits, at most a second, until no other thread of this process is running. A library's
// threads map their buffers as they start (each OpenBLAS worker 128 MB, right after the library
// is loaded, although dform never calls BLAS): read before they have, the address space in use,
// and with it the resolution offered, would depend on the scheduler.
void letOtherThreadsSettle() {
  namespace fs = std::filesystem;
  const std::string self = std::to_string(gettid());
  for (int waited = 0; waited < 1000; ++waited) {
    bool running = false;
    std::error_code error;
    for (const fs::directory_entry& task : fs::directory_iterator("/proc/self/task", error)) {
      if (task.path().filename() == self) continue;
      std::ifstream in(task.path() / "stat");
      std::string stat;
      std::getline(in, stat);
      const std::size_t name = stat.rfind(')');  // "tid (name) state ...": the name may hold ')'
      running =
          running || (name != std::string::npos && name + 2 < stat.size() && stat[name + 2] == 'R');
    }
    if (!running) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

// The address space this process had mapped as it started, under an address-space limit (kB,
// /proc/self/status VmSize once the libraries' threads have settled; 0 without a limit). Read
// once, before any thread of dform's runs: what is mapped later depends on the scheduler (a
// finished thread's 8 MB stack is reused, or a new one mapped when the next thread starts before
// the kernel has let the old one go), and the room, and the resolution offered, would with it.
// What the run maps since is in the estimate (its 64 MB for the program itself).
const double startMappedKb = [] {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0.0;
  letOtherThreadsSettle();
  return std::max(0.0, readNumber("/proc/self/status", "VmSize:"));
}();

// Bytes of address space this process may still map under RLIMIT_AS (ulimit -v), or -1 when
// unlimited: the limit less what was mapped as it started.
double addressSpaceRoom() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return -1.0;
  return std::max(0.0, double(limit.rlim_cur) - startMappedKb * 1024.0);
}

}  // namespace

std::size_t availableMemoryBytes() {
  const double availableKb = readNumber("/proc/meminfo", "MemAvailable:");
  double available = availableKb > 0 ? availableKb * 1024.0 : 0.0;
  const auto lowerTo = [&available](double room) {
    available = available > 0 ? std::min(available, room) : room;
  };
  const std::string cgroup = cgroupFolder();
  const double limit = readNumber(cgroup + "/memory.max");
  const double used = readNumber(cgroup + "/memory.current");
  if (limit > 0 && used >= 0) lowerTo(std::max(0.0, limit - used));
  if (const double room = addressSpaceRoom(); room >= 0) lowerTo(room);
  return std::size_t(available);
}

std::size_t estimatedPeakBytes(double vertices, double extraBytes) {
  const double perVertex =
      vertices <= detail::kDirectSolveVertices ? kBytesPerVertexDirect : kBytesPerVertexRelaxed;
  return std::size_t(kProgramBytes + perVertex * vertices + extraBytes);
}

namespace {

// Bytes as a person reads them, in MB below a gigabyte (to 0.1 MB) and in GB above (to 0.01 GB),
// rounded up or down: a need rounded up and a limit rounded down never print alike where the
// need exceeds the limit.
std::string bytesText(double bytes, bool roundUp) {
  const bool gigabytes = bytes >= 1e9;
  const double step = gigabytes ? 1e7 : 1e5, units = bytes / step;
  const double rounded = (roundUp ? std::ceil(units) : std::floor(units)) * step;
  char text[32];
  if (gigabytes)
    std::snprintf(text, sizeof text, "%.2f GB", rounded / 1e9);
  else
    std::snprintf(text, sizeof text, "%.1f MB", rounded / 1e6);
  return text;
}

double peakAt(const MemoryAtResolution& estimateAt, int resolution) {
  const MemoryEstimate at = estimateAt(resolution);
  return double(estimatedPeakBytes(at.vertices, at.extraBytes));
}

// The highest resolution below `resolution` whose estimate, by the run's own formula, stays
// within `budget`; 0 when not even the lowest does. Every one is tried (the formula is a few
// operations each): the pre-D-Form's tables do not grow monotonically with the resolution.
int highestFitting(const MemoryAtResolution& estimateAt, int resolution, double budget) {
  for (int fits = resolution - 1; fits >= kMinResolution; --fits)
    if (peakAt(estimateAt, fits) <= budget) return fits;
  return 0;
}

std::string offerText(int fits) {
  return fits > 0 ? "a resolution of " + std::to_string(fits) + " or less fits"
                  : "no resolution fits";
}

}  // namespace

Status checkMemory(const MemoryAtResolution& estimateAt, int resolution, const std::string& what) {
  const double available = double(availableMemoryBytes());
  if (available <= 0) return Status::ok();  // unknown: nothing to hold the run to
  const double budget = kUsableFraction * available;
  const double needed = peakAt(estimateAt, resolution);
  if (needed <= budget) return Status::ok();
  char vertices[32], share[8];
  std::snprintf(vertices, sizeof vertices, "%.0f", estimateAt(resolution).vertices);
  std::snprintf(share, sizeof share, "%.0f %%", 100 * kUsableFraction);
  return Status(ErrorCode::Usage,
                what + " at resolution " + std::to_string(resolution) + " would need about " +
                    bytesText(needed, true) + " of memory (about " + vertices +
                    " vertices), more than the " + bytesText(budget, false) + " a run may use (" +
                    share + " of the " + bytesText(available, false) + " available to it); " +
                    offerText(highestFitting(estimateAt, resolution, budget)));
}

Status outOfMemory(const MemoryAtResolution& estimateAt, int resolution, const std::string& what) {
  // The run needed more than its estimate: the resolution offered is held to half of what the
  // estimate adds to the program's own memory, and to what checkMemory would let a run use now
  // (without an estimate, the resolution of half the vertices).
  int fits = std::max(kMinResolution, int(resolution / std::sqrt(2.0)));
  if (estimateAt) {
    const double program = double(estimatedPeakBytes(0.0));
    double budget = program + 0.5 * (peakAt(estimateAt, resolution) - program);
    if (const double available = double(availableMemoryBytes()); available > 0)
      budget = std::min(budget, kUsableFraction * available);
    fits = highestFitting(estimateAt, resolution, budget);
  }
  return Status(ErrorCode::Usage,
                what + " at resolution " + std::to_string(resolution) +
                    " ran out of memory (more than its estimate: the machine or its limits, e.g. "
                    "ulimit -v, gave it less than it needed); " +
                    offerText(fits) + " in half the memory");
}

}  // namespace dform
