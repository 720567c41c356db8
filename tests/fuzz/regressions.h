// SPDX-License-Identifier: GPL-3.0-or-later
// Regression tests for the inputs that once crashed a fuzz target. Each lives in
// tests/fuzz/regressions/<target>/ (which the fuzz targets also take as seeds), and the module
// whose reader it crashed lists it with the outcome it must now have: no crash, and a proper
// Status. A file in the folder that no test lists fails the test, so none is forgotten.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "dform/core/status.h"

namespace dform::test {

/// What reading one regression input must give: `code` (Ok when the input is acceptable), and
/// for an error a message that mentions `mentions`.
struct Regression {
  std::string file;  ///< name inside tests/fuzz/regressions/<target>/
  ErrorCode code;
  std::string mentions;
};

/// Reads every input of `target` with `read(text, source)` (source is the file's path) and checks
/// the outcome against `expected`: every file in the folder is listed, each gives the code, and
/// for an error a message that is one line without control characters, starts with the source
/// and mentions the expected words. Fails listing every input that does not, so that a test says
/// EXPECT_TRUE(regressionsHold(...)) and shows them all.
inline ::testing::AssertionResult regressionsHold(
    const std::string& target, const std::vector<Regression>& expected,
    const std::function<Status(const std::string&, const std::string&)>& read) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(DFORM_FUZZ_REGRESSIONS_DIR) / target;
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  std::vector<std::string> listed;
  for (const Regression& r : expected) listed.push_back(r.file);
  std::sort(listed.begin(), listed.end());

  std::ostringstream problems;
  if (files != listed)
    problems << "\n" << dir.string() << ": every file needs its expected outcome in the test";
  for (const Regression& r : expected) {
    const std::string source = (dir / r.file).string();
    std::ifstream in(source, std::ios::binary);
    if (!in.good()) {
      problems << "\n" << source << ": cannot be read";
      continue;
    }
    std::ostringstream text;
    text << in.rdbuf();
    const Status status = read(text.str(), source);
    const std::string& m = status.message();
    if (status.code() != r.code) problems << "\n" << source << ": wrong code: " << m;
    if (status.isOk()) continue;
    if (m.rfind(source + ": ", 0) != 0)
      problems << "\n" << source << ": does not start the message: " << m;
    if (m.find(r.mentions) == std::string::npos)
      problems << "\n" << source << ": message does not mention \"" << r.mentions << "\": " << m;
    if (std::any_of(m.begin(), m.end(),
                    [](char c) { return ((unsigned char)c < 0x20 && c != '\t') || c == 0x7f; }))
      problems << "\n" << source << ": message has a control character: " << m;
  }
  if (problems.str().empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "regressions of " << target << ":" << problems.str();
}

}  // namespace dform::test
