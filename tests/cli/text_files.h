// Reading what a dform process wrote, for the CLI tests that run it (sweep, batch).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dform::test {

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

}  // namespace dform::test
