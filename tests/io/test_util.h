// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers for the io tests: a scratch folder per test, and checks on Status messages.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "dform/core/status.h"

namespace dform::test {

/// A fresh folder named after the running test (and the process, since ctest runs tests in
/// parallel), removed when the test ends.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("dform_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string path() const { return path_.string(); }

  /// Writes `content` to `name` inside the folder and returns its path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::string file = (path_ / name).string();
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }

 private:
  std::filesystem::path path_;
};

/// The status has `code`, a one-line message that starts with the file path, and mentions `part`.
inline ::testing::AssertionResult failsWith(const Status& status, ErrorCode code,
                                            const std::string& path, const std::string& part = "") {
  if (status.isOk()) return ::testing::AssertionFailure() << "expected an error, got Ok";
  const std::string& m = status.message();
  if (status.code() != code)
    return ::testing::AssertionFailure()
           << "code " << int(status.code()) << " instead of " << int(code) << ": " << m;
  if (m.rfind(path + ": ", 0) != 0)
    return ::testing::AssertionFailure() << "message does not start with the path: " << m;
  if (m.find('\n') != std::string::npos)
    return ::testing::AssertionFailure() << "message has several lines: " << m;
  if (m.find(part) == std::string::npos)
    return ::testing::AssertionFailure() << "message lacks \"" << part << "\": " << m;
  return ::testing::AssertionSuccess() << m;
}

}  // namespace dform::test
