// SPDX-License-Identifier: GPL-3.0-or-later
// Reading a user's file whole, with a size limit. Every reader of input files goes through it, so
// that no file (a huge one, a FIFO, one that grows while it is read) can exhaust memory.
#pragma once

#include <cstddef>
#include <string>

#include "dform/core/status.h"

namespace dform {

/// Outlines, seam curves, result models: no drawing needs more, and reading an arbitrary huge
/// file into memory would be a denial of service.
constexpr std::size_t kMaxInputBytes = std::size_t(64) << 20;

/// Job, gate and profile files hold a few dozen settings (under 2 KiB); a megabyte is already
/// absurd for them.
constexpr std::size_t kMaxSettingsBytes = std::size_t(1) << 20;

/// The path that names standard input, as a command-line argument (docs/cli.md).
inline const std::string kStandardInput = "-";

/// What messages call the input `path`: "stdin" for kStandardInput, else the path.
std::string inputName(const std::string& path);

/// Reads the whole file, or InputUnreadable naming it (missing, a folder, unreadable, larger than
/// `maxBytes`). kStandardInput reads standard input, once per process: every later read of it
/// gives the same bytes (or the same error).
Result<std::string> readInputFile(const std::string& path, std::size_t maxBytes = kMaxInputBytes);

}  // namespace dform
