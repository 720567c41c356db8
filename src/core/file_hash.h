// Content hashes of input files, so that a report says exactly which bytes a result came from.
#pragma once

#include <string>

#include "core/status.h"

namespace dform {

/// The SHA-256 of the file's bytes as 64 lower-case hex digits. InputUnreadable naming the file
/// when it cannot be read.
Result<std::string> sha256OfFile(const std::string& path);

}  // namespace dform
