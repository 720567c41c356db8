// SPDX-License-Identifier: GPL-3.0-or-later
// Hershey single-stroke fonts (.jhf from Debian's hershey-fonts-data), read at run time. A glyph
// line is: 5-character number, 3-character vertex count, then that many coordinate pairs, each a
// character offset from 'R'; the first pair is the glyph's left and right extent and " R" lifts
// the pen. Long glyphs continue on the next line. Capitals span y = -12 (top) to 9 (baseline).
#include <fstream>
#include <sstream>

#include "internal.h"

namespace dform::fab {

namespace {
constexpr int kFirstChar = 32;     // the .jhf files list ASCII 32..126 in order
constexpr double kCapTop = -12.0;  // font units
constexpr double kBaseline = 9.0;  // font units
constexpr double kCapHeight = kBaseline - kCapTop;
}  // namespace

Result<StrokeFont> StrokeFont::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    return Status{ErrorCode::InputUnreadable,
                  path +
                      ": cannot read the Hershey font (install the Debian package "
                      "hershey-fonts-data; scripts/install-deps does)"};
  }
  StrokeFont font;
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 10 || line.find_first_not_of(" \r") == std::string::npos) continue;
    int count = 0;
    try {
      count = std::stoi(line.substr(5, 3));
    } catch (const std::exception&) {
      return Status{ErrorCode::InputInvalid, path + ": not a Hershey .jhf font"};
    }
    std::string data = line.substr(8);
    while (int(data.size()) < 2 * count) {
      std::string more;
      if (!std::getline(in, more)) break;
      data += more;
    }
    while (!data.empty() && (data.back() == '\r' || data.back() == '\n')) data.pop_back();
    if (int(data.size()) < 2 * count || count < 1)
      return Status{ErrorCode::InputInvalid, path + ": truncated glyph in the Hershey font"};
    Glyph g;
    g.left = data[0] - 'R';
    g.right = data[1] - 'R';
    std::vector<Vec2> stroke;
    for (int i = 1; i < count; ++i) {
      const char cx = data[2 * i], cy = data[2 * i + 1];
      if (cx == ' ' && cy == 'R') {
        if (stroke.size() > 1) g.strokes.push_back(stroke);
        stroke.clear();
        continue;
      }
      stroke.emplace_back(cx - 'R', cy - 'R');
    }
    if (stroke.size() > 1) g.strokes.push_back(stroke);
    font.glyphs_.push_back(std::move(g));
  }
  if (font.glyphs_.size() < size_t('~' - kFirstChar + 1))
    return Status{ErrorCode::InputInvalid, path + ": the font has fewer than 95 glyphs"};
  return font;
}

const StrokeFont::Glyph& StrokeFont::glyph(char c) const {
  int index = int(uint8_t(c)) - kFirstChar;
  if (index < 0 || index >= int(glyphs_.size())) index = '?' - kFirstChar;
  return glyphs_[size_t(index)];
}

double StrokeFont::width(const std::string& text, double height) const {
  double units = 0;
  for (char c : text) units += glyph(c).right - glyph(c).left;
  return units * height / kCapHeight;
}

std::vector<Polyline> StrokeFont::layout(const std::string& text, const Vec2& center,
                                         const Vec2& dir, double height) const {
  const double scale = height / kCapHeight;
  const Vec2 down(-dir.y(), dir.x());  // y down: the glyph's +y axis
  const double total = width(text, height);
  const double midY = 0.5 * (kCapTop + kBaseline);
  std::vector<Polyline> out;
  double pen = -0.5 * total;  // mm along dir from the centre
  for (char c : text) {
    const Glyph& g = glyph(c);
    for (const auto& stroke : g.strokes) {
      Polyline p;
      p.reserve(stroke.size());
      for (const Vec2& q : stroke) {
        const double x = pen + (q.x() - g.left) * scale;
        const double y = (q.y() - midY) * scale;
        p.push_back(center + x * dir + y * down);
      }
      out.push_back(std::move(p));
    }
    pen += (g.right - g.left) * scale;
  }
  return out;
}

}  // namespace dform::fab
