// SPDX-License-Identifier: GPL-3.0-or-later
// The documented exit codes (README "Exit codes"): the one place that maps an error kind to the
// code the command returns, a batch manifest records and Python's dform.Error carries.
#pragma once

#include "dform/core/status.h"

namespace dform {

/// The exit code of an error kind: 0 ok, 1 internal, 2 usage, 3 input unreadable, 4 input
/// invalid, 5 solve failed, 6 output failed, 7 gate failed, 130 interrupted.
int exitCode(ErrorCode code);

}  // namespace dform
