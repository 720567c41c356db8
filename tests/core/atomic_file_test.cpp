// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace dform {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, WritesWholeFileAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / "dform_atomic_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  ASSERT_TRUE(writeFileAtomically(path, "hello\n").isOk());
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "hello\n");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, MissingFolderIsAnOutputError) {
  const Status s = writeFileAtomically("/nonexistent-dform-dir/x.txt", "data");
  EXPECT_EQ(s.code(), ErrorCode::OutputFailed);
  EXPECT_NE(s.message().find("/nonexistent-dform-dir/x.txt"), std::string::npos);
}

}  // namespace
}  // namespace dform
