// The fabrication part of the quality gate, measured on the laid-out pattern rather than trusted
// from its construction: everything on the sheet, glue tabs clear of each other and of both
// pieces, the pieces clear of each other, labels inside their piece and clear of each other. A
// piece is its material: the outline minus its holes.
#include <string>

#include "export/internal.h"
#include "export/plane_geometry.h"

namespace dform::fab {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Labels are the engraved or printed texts: tick numbers, piece names, the failed-gate mark, and
// the sheet's title, note and calibration label.
bool isLabel(const Path& p) {
  return endsWith(p.id, "-label") || endsWith(p.id, "-name") || endsWith(p.id, "-failed-gate") ||
         p.id == "title" || p.id == "note";
}

// The piece a path belongs to, from its id ("A-tick-07-label" -> A), or -1.
int pieceOf(const Path& p, const std::vector<PieceInfo>& pieces) {
  for (size_t i = 0; i < pieces.size(); ++i)
    if (p.id.rfind(pieces[i].name + "-", 0) == 0) return int(i);
  return -1;
}

void note(LayoutFindings& f, const std::string& what) {
  if (f.example.empty()) f.example = what;
}

}  // namespace

LayoutFindings checkLayout(const PatternBuild& pattern) {
  LayoutFindings f;
  const Drawing& d = pattern.drawing;
  // Off the sheet by more than rounding (1e-6 mm on coordinates of at most a few metres).
  const double eps = 1e-6;
  std::vector<const Path*> labels;
  for (const Layer& layer : d.layers)
    for (const Path& path : layer.paths) {
      bool outside = false;
      for (const Polyline& part : path.parts)
        for (const Vec2& q : part)
          outside = outside || q.x() < -eps || q.y() < -eps || q.x() > d.width + eps ||
                    q.y() > d.height + eps;
      if (outside) {
        ++f.outsideSheet;
        note(f, path.id + " runs off the " + std::to_string(int(d.width)) + " x " +
                    std::to_string(int(d.height)) + " mm sheet");
      }
      if (isLabel(path)) labels.push_back(&path);
    }

  const std::vector<PieceInfo>& pieces = pattern.pieces;
  const std::vector<TabInfo>& tabs = pattern.tabs;
  for (size_t i = 0; i < tabs.size(); ++i) {
    for (size_t j = i + 1; j < tabs.size(); ++j)
      if (overlapArea(tabs[i].polygon, tabs[j].polygon) > kOverlapTolMm2) {
        ++f.overlappingTabs;
        note(f,
             "glue tabs " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " overlap");
      }
    // Its own piece (it is attached along the fold line, which shares no area; a tab on a hole's
    // seam lies in the hole) and the other one.
    for (size_t p = 0; p < pieces.size(); ++p)
      if (overlapArea({tabs[i].polygon}, pieces[p].boundaries) > kOverlapTolMm2) {
        ++f.tabsOverPieces;
        note(f, "glue tab " + std::to_string(i + 1) + " overlaps piece " + pieces[p].name);
      }
  }
  // Each piece's cut region: its outer cut paths and its holes' (even-odd).
  auto cutRegion = [](const PieceInfo& piece) {
    std::vector<Polyline> region = piece.cut;
    region.insert(region.end(), piece.holeCuts.begin(), piece.holeCuts.end());
    return region;
  };
  if (pieces.size() == 2 &&
      overlapArea(cutRegion(pieces[0]), cutRegion(pieces[1])) > kOverlapTolMm2) {
    f.overlappingPieces = 1;
    note(f, "the cut paths of " + pieces[0].name + " and " + pieces[1].name + " overlap");
  }

  std::vector<Polyline> hulls;
  for (const Path* label : labels) {
    hulls.push_back(convexHull(label->parts));  // the footprint two labels must not share
    // A piece's labels lie inside it; the sheet's own (title, calibration bar) only on the sheet.
    const int p = pieceOf(*label, pieces);
    if (p < 0) continue;
    bool inside = true;
    for (const Polyline& part : label->parts)
      for (const Vec2& q : part) inside = inside && insideRegion(pieces[size_t(p)].boundaries, q);
    if (!inside) {
      ++f.labelsOutside;
      note(f, "label " + label->id + " is not inside its piece");
    }
  }
  for (size_t i = 0; i < hulls.size(); ++i)
    for (size_t j = i + 1; j < hulls.size(); ++j)
      if (hulls[i].size() >= 3 && hulls[j].size() >= 3 &&
          overlapArea(hulls[i], hulls[j]) > kOverlapTolMm2) {
        ++f.overlappingLabels;
        note(f, "labels " + labels[i]->id + " and " + labels[j]->id + " overlap");
      }
  return f;
}

}  // namespace dform::fab
