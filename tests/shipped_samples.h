// SPDX-License-Identifier: GPL-3.0-or-later
// The shipped samples as a user runs them: the forward job files and the inverse curves (OBJ or
// JSON) under samples/, as "forward/<file>" and "inverse/<file>", sorted. For the tests that run
// every one of them (DFORM_SAMPLES_DIR is set by dform_add_test).
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace dform::test {

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
