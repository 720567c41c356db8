// SPDX-License-Identifier: GPL-3.0-or-later
// Files are written whole or not at all: to a temporary name beside the target, then renamed.
#pragma once

#include <string>

#include "dform/core/status.h"

namespace dform {

/// Writes `content` to `path` atomically: into a new temporary file beside it
/// (`PATH.tmp.PID`, created by this call and never opened through a symbolic link), then renamed
/// over `path` (a link at `path` is replaced, not followed). OutputFailed naming the path when
/// the folder is missing or unwritable, or when something stands at the temporary path.
Status writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace dform
