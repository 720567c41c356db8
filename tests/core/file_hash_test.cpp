// SHA-256 of input files against the FIPS 180-2 test vectors, across the read buffer's edge.
#include "core/file_hash.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace dform {
namespace {

std::string hashOf(const std::string& bytes) {
  const auto path =
      std::filesystem::temp_directory_path() / ("dform_hash_" + std::to_string(getpid()));
  std::ofstream(path, std::ios::binary) << bytes;
  const Result<std::string> hash = sha256OfFile(path.string());
  std::filesystem::remove(path);
  EXPECT_TRUE(hash.isOk()) << hash.status().message();
  return hash.isOk() ? hash.value() : "";
}

TEST(FileHash, KnownVectors) {
  EXPECT_EQ(hashOf(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(hashOf("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // One million 'a': longer than the 64 KiB read buffer, so the pieces are joined correctly.
  EXPECT_EQ(hashOf(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(FileHash, MissingFileIsUnreadableAndNamed) {
  const Result<std::string> hash = sha256OfFile("/nonexistent/piece.svg");
  ASSERT_FALSE(hash.isOk());
  EXPECT_EQ(hash.status().code(), ErrorCode::InputUnreadable);
  EXPECT_NE(hash.status().message().find("/nonexistent/piece.svg"), std::string::npos);
}

}  // namespace
}  // namespace dform
