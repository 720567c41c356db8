// SPDX-License-Identifier: GPL-3.0-or-later
// The shipped samples as a user runs them: the forward job files and the inverse curves (OBJ or
// JSON) under samples/, as "forward/<file>" and "inverse/<file>", sorted. For the tests that run
// every one of them, and the paths of sample files (DFORM_SAMPLES_DIR is set by dform_add_test).
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace dform::test {

/// The path of a file under samples/, e.g. samplePath("forward/circle.svg").
inline std::string samplePath(const std::string& name) {
  return std::string(DFORM_SAMPLES_DIR) + "/" + name;
}
/// The path of a file under samples/forward/.
inline std::string forwardSample(const std::string& name) { return samplePath("forward/" + name); }
/// The path of a file under samples/inverse/.
inline std::string inverseSample(const std::string& name) { return samplePath("inverse/" + name); }

inline std::vector<std::string> shippedSamples() {
  std::vector<std::string> samples;
  for (const char* folder : {"forward", "inverse"})
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(DFORM_SAMPLES_DIR) + "/" + folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".json" || (ext == ".obj" && std::string(folder) == "inverse"))
        samples.push_back(std::string(folder) + "/" + entry.path().filename().string());
    }
  std::sort(samples.begin(), samples.end());
  return samples;
}

}  // namespace dform::test
