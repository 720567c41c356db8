#include "model/resources.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "model/run_control.h"

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

// Bytes of address space this process may still map under RLIMIT_AS (ulimit -v), or -1 when
// unlimited: the limit less what is mapped once the other threads have settled
// (/proc/self/status VmSize, kB).
double addressSpaceRoom() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return -1.0;
  letOtherThreadsSettle();
  const double mappedKb = readNumber("/proc/self/status", "VmSize:");
  return std::max(0.0, double(limit.rlim_cur) - std::max(0.0, mappedKb) * 1024.0);
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

// Vertices and the pre-D-Form's tables both grow with the square of the resolution, the seam's
// vertices only linearly, so the square underestimates a lower resolution's count: the
// resolution offered is held to 85 % of the budget (the seam is at most ~10 % of the vertices
// at the resolutions this refuses), so that it is really accepted when tried.
constexpr double kOfferedFraction = 0.85;

// The highest resolution (down to 8, in 5 % steps) whose estimated peak stays within `budget`.
int resolutionFitting(const MemoryEstimate& estimate, int resolution, double budget) {
  int fits = resolution;
  while (fits > 8) {
    const double s = double(fits) / double(resolution);
    if (double(estimatedPeakBytes(estimate.vertices * s * s, estimate.extraBytes * s * s)) <=
        budget)
      break;
    fits = std::max(8, int(fits * 0.95));
  }
  return fits;
}

}  // namespace

Status checkMemory(const MemoryEstimate& estimate, int resolution, const std::string& what) {
  const double available = double(availableMemoryBytes());
  if (available <= 0) return Status::ok();  // unknown: nothing to hold the run to
  const double budget = kUsableFraction * available;
  const double needed = double(estimatedPeakBytes(estimate.vertices, estimate.extraBytes));
  if (needed <= budget) return Status::ok();
  const int fits = resolutionFitting(estimate, resolution, kOfferedFraction * budget);
  char text[320];
  std::snprintf(text, sizeof text,
                "%s at resolution %d would need about %.1f GB of memory (about %.0f vertices) and "
                "%.1f GB is available to it; a resolution of %d or less fits",
                what.c_str(), resolution, needed / 1e9, estimate.vertices, available / 1e9, fits);
  return Status(ErrorCode::Usage, text);
}

Status outOfMemory(const MemoryEstimate& estimate, int resolution, const std::string& what) {
  // The run needed more than its estimate: the resolution offered is held to half the estimate
  // (half the vertices where nothing was estimated yet) and to what is available now.
  double budget = 0.5 * double(estimatedPeakBytes(estimate.vertices, estimate.extraBytes));
  if (const double available = double(availableMemoryBytes()); available > 0)
    budget = std::min(budget, kOfferedFraction * kUsableFraction * available);
  const int fits = estimate.vertices > 0 ? resolutionFitting(estimate, resolution, budget)
                                         : std::max(8, int(resolution / std::sqrt(2.0)));
  char text[320];
  std::snprintf(
      text, sizeof text,
      "%s at resolution %d ran out of memory (more than its estimate: the machine or its "
      "limits, e.g. ulimit -v, gave it less than it needed); a resolution of %d or less fits "
      "in half the memory",
      what.c_str(), resolution, fits);
  return Status(ErrorCode::Usage, text);
}

}  // namespace dform
