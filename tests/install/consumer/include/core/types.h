// SPDX-License-Identifier: GPL-3.0-or-later
// This project's own core/types.h, ahead of dform's headers on every include path of the
// project: dform's headers include theirs as "dform/core/types.h", so this one never stands in
// for it (were it found in its place, dform::DForm would not be declared).
#pragma once

namespace consumer {
struct Point {
  double x = 0, y = 0;
};
}  // namespace consumer
