// SPDX-License-Identifier: GPL-3.0-or-later
// What the nest tests measure on a laid-out nest: the share of the used sheets' area within the
// pieces' boxes, the sheets a plain greedy shelf packing of the same pieces takes (the yardstick a
// nest must meet), and the pieces' distance apart in the written sheets' DXF files (check_nest.py).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "export/internal.h"
#include "test_util.h"

namespace dform::test {

struct NestFigures {
  double boxShare = 0;  // the pieces' cut boxes' area over the used sheets' area
};

inline NestFigures nestFigures(const fab::PatternBuild& built) {
  double boxes = 0, sheets = 0;
  for (const fab::PieceInfo& piece : built.pieces) {
    const fab::Box b = fab::boxOf(piece.cut);
    boxes += b.w() * b.h();
  }
  for (const fab::Box& sheet : built.sheets) sheets += sheet.w() * sheet.h();
  return {sheets > 0 ? boxes / sheets : 0};
}

// The sheets a greedy shelf packing takes for the nest's pieces: each piece's cut box with its
// ticks (1.5 mm out), turned to lie flat, the tallest first, in rows left to right across the
// W x H sheet less its margins, kerf + 1 mm apart, a new row under the last, a new sheet when a
// row does not fit.
inline int shelfSheets(const fab::PatternBuild& built, double W, double H) {
  const double m = built.profile.marginMm, gap = built.profile.kerfMm + 1.0;
  std::vector<Vec2> sizes;
  for (const fab::PieceInfo& piece : built.pieces) {
    const fab::Box b = fab::boxOf(piece.cut);
    const Vec2 s(b.w() + 3, b.h() + 3);
    sizes.push_back(s.x() >= s.y() ? s : Vec2(s.y(), s.x()));
  }
  std::stable_sort(sizes.begin(), sizes.end(),
                   [](const Vec2& a, const Vec2& b) { return a.y() > b.y(); });
  const double w = W - 2 * m, h = H - 2 * m;
  int sheets = 0;
  double x = 0, y = 0, row = 0;
  for (const Vec2& s : sizes) {
    if (sheets > 0 && x + s.x() > w) {
      x = 0;
      y += row + gap;
      row = 0;
    }
    if (sheets == 0 || y + s.y() > h) {
      ++sheets;
      x = y = row = 0;
    }
    x += s.x() + gap;
    row = std::max(row, s.y());
  }
  return sheets;
}

// check_nest.py on the written sheets' DXF files: every two pieces' outer cuts `gap` mm apart.
inline void expectPiecesApart(const std::string& dir, size_t sheets, double gap) {
  std::string files;
  if (sheets == 1) files = " '" + dir + "/pattern.dxf'";
  for (size_t k = 1; sheets > 1 && k <= sheets; ++k)
    files += " '" + dir + "/" + sheetFileName(int(k), "dxf") + "'";
  std::string out;
  EXPECT_EQ(run(std::string(DFORM_PYTHON3) + " '" + DFORM_NEST_CHECKER + "' " +
                    std::to_string(gap) + files,
                &out),
            0)
      << out;
  std::printf("%s", out.c_str());
}

}  // namespace dform::test
