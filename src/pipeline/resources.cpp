#include "pipeline/resources.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pipeline/run_util.h"

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
constexpr double kBytesPerVertexDirect = 36.0 * 1024;   // measured: 690 MB at 19k vertices
constexpr double kBytesPerVertexRelaxed = 9.0 * 1024;   // measured: 790 MB at 97k vertices
constexpr double kUsableFraction = 0.8;

}  // namespace

std::size_t availableMemoryBytes() {
  const double availableKb = readNumber("/proc/meminfo", "MemAvailable:");
  double available = availableKb > 0 ? availableKb * 1024.0 : 0.0;
  const double limit = readNumber("/sys/fs/cgroup/memory.max");
  const double used = readNumber("/sys/fs/cgroup/memory.current");
  if (limit > 0 && used >= 0) {
    const double room = std::max(0.0, limit - used);
    available = available > 0 ? std::min(available, room) : room;
  }
  return std::size_t(available);
}

std::size_t estimatedPeakBytes(double vertices, double extraBytes) {
  const double perVertex =
      vertices <= detail::kDirectSolveVertices ? kBytesPerVertexDirect : kBytesPerVertexRelaxed;
  return std::size_t(kProgramBytes + perVertex * vertices + extraBytes);
}

Status checkMemory(double vertices, double extraBytes, int resolution, const std::string& what) {
  const double available = double(availableMemoryBytes());
  if (available <= 0) return Status::ok();  // unknown: nothing to hold the run to
  const double budget = kUsableFraction * available;
  if (double(estimatedPeakBytes(vertices, extraBytes)) <= budget) return Status::ok();
  // Vertices and the pre-D-Form's tables both grow with the square of the resolution.
  int fits = resolution;
  while (fits > 8) {
    const double s = double(fits) / double(resolution);
    if (double(estimatedPeakBytes(vertices * s * s, extraBytes * s * s)) <= budget) break;
    fits = std::max(8, int(fits * 0.95));
  }
  char text[320];
  std::snprintf(text, sizeof text,
                "%s at resolution %d would need about %.1f GB of memory (about %.0f vertices) and "
                "the machine has %.1f GB available; a resolution of %d or less fits",
                what.c_str(), resolution, double(estimatedPeakBytes(vertices, extraBytes)) / 1e9, vertices,
                available / 1e9, fits);
  return Status(ErrorCode::Usage, text);
}

}  // namespace dform
