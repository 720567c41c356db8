// SPDX-License-Identifier: GPL-3.0-or-later
// Packing a nest's parts (rectangles, each at either of two turns) on as few sheets as hold them
// (nest_pack.cpp). Internal to the export module.
#pragma once

#include <vector>

#include "internal.h"

namespace dform::fab {

// A part to pack: its extent (mm) at each of its two turns.
struct PackItem {
  Vec2 size[2];
};

// Where a part went: its turn, its sheet, and the top-left corner of its extent in the sheet's
// region (mm from the region's top left).
struct PackPlacement {
  int item = 0, turn = 0, sheet = 0;
  Vec2 at = Vec2::Zero();
};

struct Packing {
  std::vector<PackPlacement> placed;
  int sheets = 0;  // 0: some part fits no sheet
};

// The parts on as few `region`-sized sheets as hold them, `gap` mm apart and inside the region,
// each sheet keeping a `reserved` box clear at its bottom left (the mark): the best of several
// greedy packings (MaxRects with three rules, shelves; each with the parts by area, by longest
// and by shortest side). No placement when a part fits no sheet at either turn.
Packing packParts(const std::vector<PackItem>& items, const Vec2& region, double gap,
                  const Vec2& reserved);

}  // namespace dform::fab
