// SPDX-License-Identifier: GPL-3.0-or-later
// The fabrication part of the quality gate, measured on the laid-out pattern rather than trusted
// from its construction: everything on the sheet, glue tabs clear of each other and of both
// pieces, the pieces clear of each other, labels inside their piece and clear of each other. A
// piece is its material: the outline minus its holes. Shapes are compared pairwise only where
// their boxes meet (a grid of boxes finds those pairs), so the check costs about as much as the
// pattern has shapes. Every piece is cut as one loop per boundary loop, its tabs in it.
#include <algorithm>
#include <cctype>
#include <string>

#include "internal.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The id without a "-page-N" suffix (a later page's copy of the sheet furniture).
std::string withoutPage(const std::string& id) {
  const size_t at = id.rfind("-page-");
  if (at == std::string::npos || at + 6 == id.size()) return id;
  for (size_t i = at + 6; i < id.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(id[i]))) return id;
  return id.substr(0, at);
}

// Labels are the engraved or printed texts: tick numbers, piece names, the failed-gate mark, and
// the sheet's title, note and calibration label (on every page).
bool isLabel(const Path& p) {
  const std::string id = withoutPage(p.id);
  return endsWith(id, "-label") || endsWith(id, "-name") || endsWith(id, "-failed-gate") ||
         id == "title" || id == "note" || id == "tab-note" || id == "failed-gate" ||
         id == "scale-note" || id == "regmark-note";
}

// The sheet's own furniture: its title block (title, notes, legend, failed-gate line) and the
// calibration bar with its label.
bool isSheetFurniture(const Path& p) {
  const std::string id = withoutPage(p.id);
  return id == "title" || id == "note" || id == "tab-note" || id == "crease-legend-label" ||
         id == "failed-gate" || id == "calibration-bar" || id == "calibration-label" ||
         id == "job-name" || id == "scale-note" || id == "regmark-note";
}

// The piece a path belongs to, from its id ("A-tick-07-label" -> A), or -1: the piece with the
// longest name that heads the id (a nest's "x-A" and "x-A-copy2-A" both head the latter's ids).
int pieceOf(const Path& p, const std::vector<PieceInfo>& pieces) {
  int found = -1;
  for (size_t i = 0; i < pieces.size(); ++i)
    if (p.id.rfind(pieces[i].name + "-", 0) == 0 &&
        (found < 0 || pieces[i].name.size() > pieces[size_t(found)].name.size()))
      found = int(i);
  return found;
}

void note(LayoutFindings& f, const std::string& what) {
  if (f.example.empty()) f.example = what;
}

// A grid cell about the size of the shapes filed: their mean box size.
double cellFor(const std::vector<Box>& boxes) {
  double sum = 0;
  for (const Box& b : boxes) sum += std::max(b.w(), b.h());
  return boxes.empty() ? 1.0 : std::max(sum / double(boxes.size()), 1.0);
}

// The pairs (i, j), i < j, of `boxes` that meet.
std::vector<std::pair<int, int>> meetingPairs(const std::vector<Box>& boxes) {
  BoxIndex index(cellFor(boxes));
  for (size_t i = 0; i < boxes.size(); ++i) index.insert(int(i), boxes[i]);
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < boxes.size(); ++i)
    for (int j : index.overlapping(boxes[i]))
      if (j > int(i)) pairs.emplace_back(int(i), j);
  return pairs;
}

// The title block and the calibration bar keep off the pieces (their cut paths, tabs included,
// and their printed bleed) and the registration marks.
void checkSheetFurniture(const PatternBuild& pattern, LayoutFindings& f, BuildWork& work) {
  const Drawing& d = pattern.drawing;
  const std::vector<PieceInfo>& pieces = pattern.pieces;
  std::vector<Polyline> obstacles;
  std::vector<std::string> obstacleNames;
  for (const PieceInfo& piece : pieces) {
    for (const Polyline& cut : piece.cut) {
      obstacles.push_back(cut);
      obstacleNames.push_back("piece " + piece.name);
    }
    for (const Polyline& tint : piece.bleed) {
      obstacles.push_back(tint);
      obstacleNames.push_back("piece " + piece.name + "'s printed bleed");
    }
  }
  for (const Layer& layer : d.layers)
    if (layer.name == "Regmarks")
      for (const Path& mark : layer.paths) {
        obstacles.push_back(convexHull(mark.parts));
        obstacleNames.push_back("registration mark " + mark.id);
      }
  std::vector<Box> obstacleBoxes;
  for (const Polyline& o : obstacles) obstacleBoxes.push_back(boxOf({o}));
  for (const Layer& layer : d.layers)
    for (const Path& path : layer.paths) {
      if (!isSheetFurniture(path)) continue;
      const Polyline hull = convexHull(path.parts);
      const Box box = boxOf({hull});
      for (size_t k = 0; k < obstacles.size(); ++k) {
        if (hull.size() < 3 || !box.overlaps(obstacleBoxes[k])) continue;
        ++work.pairTests;
        if (overlapArea(hull, obstacles[k]) > kOverlapTolMm2) {
          ++f.titleOverlaps;
          note(f, path.id + " overlaps " + obstacleNames[k]);
        }
      }
    }
}

}  // namespace

LayoutFindings checkLayout(const PatternBuild& pattern, BuildWork* workOut) {
  BuildWork unused;
  BuildWork& work = workOut ? *workOut : unused;
  LayoutFindings f;
  const Drawing& d = pattern.drawing;
  // Off its sheet (or page) by more than rounding (1e-6 mm on coordinates of at most a few
  // metres). A pattern with a page per piece has a sheet per page, and a path on none of them (or
  // across two) is off.
  const double eps = 1e-6;
  std::vector<const Path*> labels;
  for (const Layer& layer : d.layers)
    for (const Path& path : layer.paths) {
      const Box box = boxOf(path.parts);
      const bool onASheet = std::any_of(pattern.sheets.begin(), pattern.sheets.end(),
                                        [&](const Box& sheet) { return sheet.contains(box, eps); });
      if (!onASheet) {
        ++f.outsideSheet;
        note(f, path.id + " runs off the " + std::to_string(int(d.width)) + " x " +
                    std::to_string(int(d.height)) + " mm sheet");
      }
      if (isLabel(path)) labels.push_back(&path);
    }

  const std::vector<PieceInfo>& pieces = pattern.pieces;
  const std::vector<TabInfo>& tabs = pattern.tabs;
  std::vector<Box> tabBoxes;
  for (const TabInfo& t : tabs) tabBoxes.push_back(boxOf({t.polygon}));
  for (const auto& [i, j] : meetingPairs(tabBoxes)) {
    ++work.pairTests;
    if (overlapArea(tabs[size_t(i)].polygon, tabs[size_t(j)].polygon) > kOverlapTolMm2) {
      ++f.overlappingTabs;
      note(f, "glue tabs " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " overlap");
    }
  }
  // Each tab against its own piece (it is attached along the fold line, which shares no area; a
  // tab on a hole's seam lies in the hole) and the other one.
  for (size_t p = 0; p < pieces.size(); ++p) {
    const Box pieceBox = boxOf(pieces[p].boundaries);
    for (size_t i = 0; i < tabs.size(); ++i) {
      if (!tabBoxes[i].overlaps(pieceBox)) continue;
      ++work.pairTests;
      if (overlapArea({tabs[i].polygon}, pieces[p].boundaries) > kOverlapTolMm2) {
        ++f.tabsOverPieces;
        note(f, "glue tab " + std::to_string(i + 1) + " overlaps piece " + pieces[p].name);
      }
    }
  }
  // Each piece's cut region: its outer cut paths and its holes' (even-odd).
  auto cutRegion = [](const PieceInfo& piece) {
    std::vector<Polyline> region = piece.cut;
    region.insert(region.end(), piece.holeCuts.begin(), piece.holeCuts.end());
    return region;
  };
  std::vector<Box> pieceBoxes;
  for (const PieceInfo& piece : pieces) pieceBoxes.push_back(boxOf(piece.cut));
  for (const auto& [i, j] : meetingPairs(pieceBoxes)) {
    const PieceInfo& a = pieces[size_t(i)];
    const PieceInfo& b = pieces[size_t(j)];
    if (overlapArea(cutRegion(a), cutRegion(b)) > kOverlapTolMm2) {
      ++f.overlappingPieces;
      note(f, "the cut paths of " + a.name + " and " + b.name + " overlap");
    }
  }

  checkSheetFurniture(pattern, f, work);

  // One closed cut loop per boundary loop of each piece: its outline (tabs included) and each
  // hole. A loop more is cut free of its piece (a detached tab); perforations are open paths.
  size_t loopsExpected = 0, loopsCut = 0;
  for (const PieceInfo& piece : pieces) loopsExpected += piece.boundaries.size();
  for (const Layer& layer : d.layers)
    if (layer.name == "Cut")
      for (const Path& path : layer.paths)
        if (path.closed) loopsCut += path.parts.size();
  if (loopsCut > loopsExpected) {
    f.extraCutLoops = int(loopsCut - loopsExpected);
    note(f, std::to_string(loopsCut) + " closed cut loops for " + std::to_string(pieces.size()) +
                " pieces with " + std::to_string(loopsExpected) +
                " boundary loops: a tab or a sliver would be cut free");
  }

  std::vector<Polyline> hulls;
  std::vector<Box> hullBoxes;
  for (const Path* label : labels) {
    hulls.push_back(convexHull(label->parts));  // the footprint two labels must not share
    hullBoxes.push_back(boxOf({hulls.back()}));
    // A piece's labels lie inside it; the sheet's own (title, calibration bar) only on the sheet.
    const int p = pieceOf(*label, pieces);
    if (p < 0) continue;
    // A number on a glue tab lies inside one of its piece's tabs; any other label in the piece.
    std::vector<std::vector<Polyline>> regions;
    if (endsWith(label->id, "-tab-label")) {
      for (const TabInfo& tab : tabs)
        if (tab.piece == p) regions.push_back({tab.polygon});
    } else {
      regions.push_back(pieces[size_t(p)].boundaries);
    }
    bool inside = std::any_of(regions.begin(), regions.end(), [&](const auto& region) {
      for (const Polyline& part : label->parts)
        for (const Vec2& q : part)
          if (!insideRegion(region, q)) return false;
      return true;
    });
    if (!inside) {
      ++f.labelsOutside;
      note(f, "label " + label->id + " is not inside its piece");
    }
  }
  for (const auto& [i, j] : meetingPairs(hullBoxes)) {
    const Polyline& a = hulls[size_t(i)];
    const Polyline& b = hulls[size_t(j)];
    if (a.size() < 3 || b.size() < 3) continue;
    ++work.pairTests;
    if (overlapArea(a, b) > kOverlapTolMm2) {
      ++f.overlappingLabels;
      note(f, "labels " + labels[size_t(i)]->id + " and " + labels[size_t(j)]->id + " overlap");
    }
  }
  return f;
}

}  // namespace dform::fab
