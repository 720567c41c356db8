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

#include "core/status.h"

namespace dform::test {

/// What reading one regression input must give: `code` (Ok when the input is acceptable), and
/// for an error a message that mentions `mentions`.
struct Regression {
  std::string file;  ///< name inside tests/fuzz/regressions/<target>/
  ErrorCode code;
  std::string mentions;
};

/// Reads every input of `target` with `read(text, source)` (source is the file's path) and checks
/// the outcome against `expected`: the code, and for an error a message that is one line without
/// control characters, starts with the source and mentions the expected words.
inline void checkRegressions(
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
  EXPECT_EQ(files, listed) << "every file in " << dir << " needs its expected outcome here";

  for (const Regression& r : expected) {
    const std::string source = (dir / r.file).string();
    SCOPED_TRACE(source);
    std::ifstream in(source, std::ios::binary);
    ASSERT_TRUE(in.good());
    std::ostringstream text;
    text << in.rdbuf();
    const Status status = read(text.str(), source);
    EXPECT_EQ(status.code(), r.code) << status.message();
    if (status.isOk()) continue;
    const std::string& m = status.message();
    EXPECT_EQ(m.rfind(source + ": ", 0), 0u) << m;
    EXPECT_NE(m.find(r.mentions), std::string::npos) << m;
    EXPECT_TRUE(std::none_of(m.begin(), m.end(), [](char c) {
      return ((unsigned char)c < 0x20 && c != '\t') || c == 0x7f;
    })) << m;
  }
}

}  // namespace dform::test
