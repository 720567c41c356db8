// Files are written whole or not at all: to a temporary name beside the target, then renamed.
#pragma once

#include <string>

#include "dform/core/status.h"

namespace dform {

/// Writes `content` to `path` atomically (temporary file in the same folder, then rename).
/// Returns OutputFailed naming the path when the folder is missing or unwritable.
Status writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace dform
