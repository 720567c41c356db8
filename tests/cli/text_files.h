// SPDX-License-Identifier: GPL-3.0-or-later
// Scratch folders and reading what a dform process wrote, for the CLI tests that run it.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dform::test {

/// An empty folder in the system's temporary folder named after `prefix`, the running test (none
/// in a suite's set-up) and this process, so that tests ctest runs side by side never share one.
inline std::filesystem::path freshTestFolder(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (prefix + (info ? std::string("_") + info->name() : std::string()) + "_" +
       std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The whole file, or "" when it cannot be read.
inline std::string readText(const std::filesystem::path& path) {
  std::ostringstream text;
  text << std::ifstream(path, std::ios::binary).rdbuf();
  return text.str();
}

/// How many times `what` occurs in `text`.
inline int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// What a process did: its exit code (-1 when it did not exit) and what it printed.
struct Outcome {
  int exitCode = -1;
  std::string out, err;
};

/// Runs the shell command line `command` with its stdout and stderr kept in `dir`/stdout.txt and
/// `dir`/stderr.txt.
inline Outcome runCaptured(const std::string& command, const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(out), readText(err)};
}

}  // namespace dform::test
