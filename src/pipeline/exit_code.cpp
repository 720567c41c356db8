// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/exit_code.h"

namespace dform {

int exitCode(ErrorCode code) {
  switch (code) {
    case ErrorCode::Ok: return 0;
    case ErrorCode::Internal: return 1;
    case ErrorCode::Usage: return 2;
    case ErrorCode::InputUnreadable: return 3;
    case ErrorCode::InputInvalid: return 4;
    case ErrorCode::SolveFailed: return 5;
    case ErrorCode::OutputFailed: return 6;
    case ErrorCode::GateFailed: return 7;
    case ErrorCode::Interrupted: return 130;
  }
  return 1;
}

}  // namespace dform
