// SPDX-License-Identifier: GPL-3.0-or-later
// Properties every fuzz target checks besides "no crash, no leak, no undefined behaviour": a
// reader's error is a Status whose message is one printable line naming the source, as the CLI
// prints it ("dform: error: <file>: <problem>"). A violation aborts, which libFuzzer reports.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "dform/core/status.h"

namespace dform::fuzz {

[[noreturn]] inline void violated(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "fuzz property violated: %s: %s\n", what.c_str(), detail.c_str());
  std::abort();
}

inline void require(bool holds, const std::string& what, const std::string& detail = "") {
  if (!holds) violated(what, detail);
}

/// An error names `source` first and is one line without control characters (a tab is allowed).
inline void checkStatus(const Status& status, const std::string& source) {
  if (status.isOk()) return;
  const std::string& m = status.message();
  require(m.rfind(source + ": ", 0) == 0, "the message does not start with the source", m);
  for (const char c : m)
    require(!((unsigned char)c < 0x20 && c != '\t') && c != 0x7f,
            "the message has a control character", m);
  require(status.code() != ErrorCode::Internal, "bad input reported as an internal error", m);
}

/// The input as text, for the readers' text entry points.
inline std::string text(const unsigned char* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Reads the input with `parse(text, source)` (a reader's text entry point) and checks the
/// Status; returns the Result for the target's own checks of what was accepted.
template <typename Parse>
auto parseChecked(const unsigned char* data, std::size_t size, const std::string& source,
                  Parse parse) {
  auto result = parse(text(data, size), source);
  checkStatus(result.status(), source);
  return result;
}

}  // namespace dform::fuzz
