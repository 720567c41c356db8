// SPDX-License-Identifier: GPL-3.0-or-later
// The 14 shipped samples of the shop floor's matrix: the forward job files and inverse curves
// (shipped_samples.h) and the two forward pairs the README solves from their SVGs (the ellipses,
// and circle + square), each solved by build/dform as a user would. For the tests built with
// DFORM_EXE and DFORM_SAMPLES_DIR.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "shipped_samples.h"
#include "test_util.h"

namespace dform::test {

struct MatrixSample {
  std::string name;     // the job's name: the file name without its extension
  std::string command;  // the dform command and inputs that solve it
};

inline std::vector<MatrixSample> matrixSamples() {
  const std::string dir = DFORM_SAMPLES_DIR;
  std::vector<MatrixSample> out{
      {"ellipses", "forward " + dir + "/forward/ellipses-a.svg " + dir + "/forward/ellipses-b.svg"},
      {"circle-square", "forward " + dir + "/forward/circle.svg " + dir + "/forward/square.svg"}};
  for (const std::string& sample : shippedSamples()) {
    const bool forward = sample.rfind("forward/", 0) == 0;
    const size_t slash = sample.find('/'), dot = sample.rfind('.');
    out.push_back({sample.substr(slash + 1, dot - slash - 1),
                   (forward ? "run " : "inverse ") + dir + "/" + sample});
  }
  return out;
}

inline std::string testName(const MatrixSample& sample) {
  std::string name = sample.name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// Solves `sample` into a fresh folder with build/dform (no export) and returns the folder.
inline std::string solveSample(const MatrixSample& sample, const std::string& options = "") {
  const std::string dir = freshDir("solved-" + testName(sample));
  std::string out;
  EXPECT_EQ(run(std::string(DFORM_EXE) + " " + sample.command + " --no-export -q " + options +
                    " -o " + dir,
                &out),
            0)
      << out;
  return dir;
}

}  // namespace dform::test
