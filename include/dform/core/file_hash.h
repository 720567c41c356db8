// SPDX-License-Identifier: GPL-3.0-or-later
// Content hashes of input files, so that a report says exactly which bytes a result came from.
// The readers hash the bytes they parse: a file is never opened a second time to hash it (it
// could have changed meanwhile, or be a FIFO that gives its bytes once).
#pragma once

#include <string>
#include <string_view>

namespace dform {

/// The SHA-256 of `bytes` as 64 lower-case hex digits.
std::string sha256Hex(std::string_view bytes);

}  // namespace dform
