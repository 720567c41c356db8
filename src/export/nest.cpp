// SPDX-License-Identifier: GPL-3.0-or-later
// A nest: the pieces of several D-Forms (and copies of them) on as few sheets as hold them. Each
// D-Form's pattern is laid out as usual on a sheet large enough for both pieces, once with the
// pieces at their smallest-box turn and once a quarter turn further (so that every label is
// drawn readable at either turn), its pieces named after their D-Form; each piece is then a part:
// every path whose id is the piece's, its cut region, its tabs and holes. The parts' extents are
// packed (nest_pack.cpp) `kerf + 1` mm apart and moved onto their sheets; each sheet gets the mark
// and the title lines where they fit, and the whole is checked as any pattern is.
#include <algorithm>
#include <cctype>
#include <map>
#include <memory>

#include "dform/core/interrupt.h"
#include "nest_pack.h"
#include "pattern_layout.h"

namespace dform::fab {

namespace {

// A piece of one copy of one D-Form, laid out at both turns.
struct Part {
  std::string name;  // "ellipses-A": the ids of its paths start with it and a '-'
  std::string job;
  int copy = 1;
  int piece = 0;                      // 0 = A, 1 = B of its D-Form
  const PatternBuild* built[2] = {};  // its D-Form's pattern at each turn
  Box extent[2];                      // what it draws, in that pattern's frame
};

// The paths of `built`'s drawing that are `name`'s, by layer name.
std::vector<std::pair<std::string, Path>> pathsOf(const PatternBuild& built,
                                                  const std::string& name) {
  std::vector<std::pair<std::string, Path>> out;
  for (const Layer& layer : built.drawing.layers)
    for (const Path& path : layer.paths)
      if (path.id.rfind(name + "-", 0) == 0) out.emplace_back(layer.name, path);
  return out;
}

Polyline moved(Polyline line, const Vec2& by) {
  for (Vec2& q : line) q += by;
  return line;
}

std::vector<Polyline> moved(std::vector<Polyline> lines, const Vec2& by) {
  for (Polyline& line : lines) line = moved(std::move(line), by);
  return lines;
}

// Whether `id` is one of piece `name`'s outer cut loops ("A-cut", "A-cut-2"), which a sheet cuts
// after every inner cut.
bool isOuterCut(const std::string& id, const std::string& name) {
  const std::string head = name + "-cut";
  if (id == head) return true;
  if (id.rfind(head + "-", 0) != 0 || id.size() == head.size() + 1) return false;
  return std::all_of(id.begin() + long(head.size()) + 1, id.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// The labels of `items`' copies, one per copy, unique: the job's name, "-copyK" for a later copy.
std::vector<std::pair<std::string, int>> copyLabels(const std::vector<NestItem>& items,
                                                    std::vector<int>& itemOf) {
  std::vector<std::pair<std::string, int>> labels;
  std::map<std::string, int> seen;
  for (size_t i = 0; i < items.size(); ++i)
    for (int c = 1; c <= items[i].copies; ++c) {
      std::string label = items[i].jobName + (c > 1 ? "-copy" + std::to_string(c) : "");
      for (int k = 2; seen.count(label); ++k) label += "-" + std::to_string(k);
      seen[label] = 1;
      labels.emplace_back(label, c);
      itemOf.push_back(int(i));
    }
  return labels;
}

// The profile a D-Form of the nest is laid out with: the nest's, on a sheet of its own size.
Profile unpaged(Profile profile) {
  profile.page.clear();
  profile.tile = false;
  return profile;
}

}  // namespace

namespace {

// Each copy of each D-Form laid out at both turns (into `builds`) and cut into its two parts.
Status layOutParts(const std::vector<NestItem>& items, const ExportOptions& options,
                   const Profile& profile, const StrokeFont& font,
                   std::vector<std::unique_ptr<PatternBuild>>& builds, std::vector<Part>& parts,
                   PatternBuild& out) {
  std::vector<int> itemOf;
  const std::vector<std::pair<std::string, int>> labels = copyLabels(items, itemOf);
  const Profile alone = unpaged(profile);
  for (size_t c = 0; c < labels.size(); ++c) {
    const NestItem& item = items[size_t(itemOf[c])];
    DForm model = *item.model;
    model.a.name = labels[c].first + "-" + (model.a.name.empty() ? "A" : model.a.name);
    model.b.name = labels[c].first + "-" + (model.b.name.empty() ? "B" : model.b.name);
    ExportOptions o = options;
    o.jobName = labels[c].first;
    o.title = false;
    o.scaleToFit = false;
    o.page.clear();
    o.sheetGiven = false;
    o.sheetWidthMm = o.sheetHeightMm = 1e5;  // both pieces together, each at the turn asked
    o.folds = item.folds;
    o.useProfileOverride = true;
    o.profileOverride = alone;
    const PatternBuild* built[2];
    for (int turn = 0; turn < 2; ++turn) {
      throwIfInterrupted("the nest");
      Result<PatternBuild> b = buildNestPattern(model, o, alone, font, NestLayout{turn});
      if (!b.isOk())
        return Status(b.status().code(), labels[c].first + ": " + b.status().message());
      builds.push_back(std::make_unique<PatternBuild>(std::move(b.value())));
      built[turn] = builds.back().get();
    }
    if (labels[c].second == 1) {
      for (const std::string& m : built[0]->messages)
        out.messages.push_back(item.jobName + ": " + m);
      for (const std::string& w : built[0]->warnings)
        out.warnings.push_back(item.jobName + ": " + w);
    }
    for (int p = 0; p < 2; ++p) {
      Part part;
      part.name = built[0]->pieces[size_t(p)].name;
      part.job = item.jobName;
      part.copy = labels[c].second;
      part.piece = p;
      for (int turn = 0; turn < 2; ++turn) {
        part.built[turn] = built[turn];
        for (const auto& [layer, path] : pathsOf(*built[turn], part.name))
          for (const Polyline& line : path.parts) part.extent[turn].add(line);
      }
      parts.push_back(part);
    }
  }
  return Status::ok();
}

// Part `part` at turn `turn` moved by `by` onto sheet `sheet` of the nest `out`: its paths into
// `b`'s layers of the same name (its outer cuts into `outerCuts`, which the Cut layer takes after
// every inner cut), its piece, tabs and joint holes.
void placePart(const Part& part, int turn, const Vec2& by, int sheet, DrawingBuilder& b,
               PatternBuild& out, std::vector<Path>& outerCuts) {
  const PatternBuild& built = *part.built[turn];
  for (auto& [layerName, path] : pathsOf(built, part.name)) {
    Path p = path;
    p.parts = moved(std::move(p.parts), by);
    if (layerName == "Cut" && isOuterCut(p.id, part.name)) {
      outerCuts.push_back(std::move(p));
      continue;
    }
    for (Layer& layer : b.drawing().layers)
      if (layer.name == layerName) layer.paths.push_back(p);
  }
  PieceInfo info = built.pieces[size_t(part.piece)];
  info.outline = moved(info.outline, by);
  for (auto* lines : {&info.boundaries, &info.jointLoops, &info.bleed, &info.cut, &info.holeCuts})
    *lines = moved(*lines, by);
  for (CreaseInfo& crease : info.creases) crease.line = moved(crease.line, by);
  for (ScoredFoldInfo& fold : info.scoredFolds) fold.lines = moved(fold.lines, by);
  info.sheet = sheet;
  const int index = int(out.pieces.size());
  out.pieces.push_back(std::move(info));
  for (TabInfo tab : built.tabs)
    if (tab.piece == part.piece) {
      tab.piece = index;
      tab.polygon = moved(tab.polygon, by);
      tab.fold = moved(tab.fold, by);
      out.tabs.push_back(std::move(tab));
    }
  for (JointHoleInfo hole : built.jointHoles)
    if (hole.piece == part.piece) {
      hole.piece = index;
      hole.centre += by;
      out.jointHoles.push_back(hole);
    }
}

// What the nest's title lines say: its pieces and D-Forms, its scale, kerf and gap.
TitleText nestTitle(const std::vector<Part>& parts, const ExportOptions& o, const Profile& profile,
                    const StrokeFont& font, double gap) {
  std::vector<std::string> jobs, names;
  for (const Part& part : parts) {
    names.push_back(part.name);
    if (part.piece == 0 && part.copy == 1) jobs.push_back(part.job);
  }
  std::string list;
  for (const std::string& job : jobs) list += (list.empty() ? "" : ", ") + job;
  const bool creased = std::any_of(parts.begin(), parts.end(), [](const Part& part) {
    return !part.built[0]->pieces[size_t(part.piece)].creases.empty();
  });
  return TitleText{o,
                   std::to_string(parts.size()) + " pieces of " + std::to_string(jobs.size()) +
                       " D-Forms (" + list + ")",
                   o.scale == 1.0 ? std::string("1:1, mm")
                                  : "scale " + percentText(o.scale) + " of true size, mm",
                   "kerf " + formatMm(profile.kerfMm, 2) + " mm, pieces " + formatMm(gap, 2) +
                       " mm apart or more",
                   names,
                   creased,
                   font};
}

// The mark's box (length along, depth across, mm) at the title's full height: room every sheet of
// the nest keeps for it.
Vec2 markBox(const SheetFit& fit, const TitleText& text) {
  double length = 0, depth = 0;
  for (const TitleLine& line : titleLines(0, 1, -1, false, fit, text)) {
    length = std::max(length, text.font.width(line.words, fit.textH));
    depth += kTitlePitch * fit.textH;
  }
  if (fit.profile->calibrationBar) {
    length = std::max(length, kBarLabelAt + text.font.width(barLabel(false, fit), fit.textH));
    depth += kBarRow;
  }
  return Vec2(length, depth);
}

}  // namespace

Result<LaidOutExport> layOutNestOrThrow(const std::vector<NestItem>& items,
                                        const ExportOptions& o) {
  if (items.empty()) return Status(ErrorCode::Usage, "a nest needs at least one result");
  for (const NestItem& item : items) {
    if (!item.model) return Status(ErrorCode::Internal, "layOutNest: an item without a model");
    if (item.copies < 1 || item.copies > 1000)
      return Status(ErrorCode::Usage, "the copies of a nest must be from 1 to 1000");
  }
  Result<Profile> resolved = resolveProfile(o);
  if (!resolved.isOk()) return resolved.status();
  const Profile& profile = resolved.value();
  if (Status s = checkExportOptions(o); !s.isOk()) return s;
  Result<StrokeFont> font = StrokeFont::load(o.fontPath);
  if (!font.isOk()) return font.status();
  std::vector<std::unique_ptr<PatternBuild>> builds;
  std::vector<Part> parts;
  PatternBuild out;
  if (Status s = layOutParts(items, o, profile, font.value(), builds, parts, out); !s.isOk())
    return s;
  bool tooLarge = false;
  Result<SheetFit> fitted = sheetFit(o, profile, false, o.scale, tooLarge);
  if (!fitted.isOk()) return fitted.status();
  const SheetFit& fit = fitted.value();
  const double gap = profile.kerfMm + 1.0;  // between the parts' extents, ticks included
  const TitleText text = nestTitle(parts, o, profile, font.value(), gap);
  const Box region0 = fit.artRegion(fit.pageW, fit.pageH);
  const Vec2 mark = markBox(fit, text);
  std::vector<PackItem> items2;
  for (const Part& part : parts) {
    PackItem item{{Vec2(part.extent[0].w(), part.extent[0].h()),
                   Vec2(part.extent[1].w(), part.extent[1].h())}};
    if (!fit.fits(item.size[0], fit.pageW, fit.pageH) &&
        !fit.fits(item.size[1], fit.pageW, fit.pageH))
      return fit.tooLarge("piece " + part.name, {item.size[0], item.size[1]},
                          "the piece with its tabs");
    items2.push_back(item);
  }
  const Packing packing =
      packParts(items2, Vec2(region0.w(), region0.h()), gap, mark + Vec2::Constant(gap));
  if (packing.sheets == 0)
    return Status(ErrorCode::Usage, "the pieces of the nest and its mark fit no sheet of " +
                                        formatMm(fit.pageW) + " x " + formatMm(fit.pageH) + " mm");
  const double W = fit.pageW, H = fit.pageH;
  DrawingBuilder b(profile, W * packing.sheets, H);
  std::vector<SheetPlan> plans(size_t(packing.sheets));
  std::vector<std::vector<Box>> taken(plans.size());
  std::vector<Path> outerCuts;
  for (size_t k = 0; k < plans.size(); ++k) {
    plans[k].box = Box::spanning(Vec2(W * double(k), 0), Vec2(W * double(k + 1), H));
    out.sheets.push_back(plans[k].box);
  }
  for (const PackPlacement& q : packing.placed) {
    const Part& part = parts[size_t(q.item)];
    const Box region = fit.artRegion(W, H, plans[size_t(q.sheet)].box.lo);
    const Vec2 by = region.lo + q.at - part.extent[q.turn].lo;
    plans[size_t(q.sheet)].pieces.push_back(int(out.pieces.size()));
    taken[size_t(q.sheet)].push_back(
        Box::spanning(part.extent[q.turn].lo + by, part.extent[q.turn].hi + by));
    placePart(part, q.turn, by, q.sheet, b, out, outerCuts);
    out.nestParts.push_back({part.name, part.job, part.copy, part.piece, q.sheet, 90.0 * q.turn});
  }
  b.cut().paths.insert(b.cut().paths.end(), outerCuts.begin(), outerCuts.end());
  for (size_t k = 0; k < plans.size(); ++k) {
    const Box region = fit.artRegion(W, H, plans[k].box.lo);
    plans[k].title = placeTitle(region, taken[k], k, plans.size(), -1, fit, text);
    if (!plans[k].title.placed) {  // the mark in the room the packing kept for it
      plans[k].title = TitlePlace{true, false, fit.textH, {}};
      plans[k].title.block = {Vec2(1, 0), Vec2(0, 1), Vec2(region.lo.x(), region.hi.y() - mark.y()),
                              mark.x(), 0};
    }
  }
  out.profile = profile;
  out.scale = o.scale;
  out.tickSpacing = o.tickSpacingMm;
  out.joint = jointSettings(o, profile);
  b.drawing().title = o.jobName + " - nest of D-Form pieces (" + profile.name + ")";
  b.drawing().description = "job " + o.jobName + "; profile " + profile.name + "; " + text.what +
                            " on " + std::to_string(plans.size()) + " " + fit.sheetWord +
                            "(s); 1 user unit = 1 mm";
  drawSheetFurniture(plans, fit, text, b);
  out.drawing = std::move(b.drawing());
  addPages(plans, fit, text, out);
  LaidOutExport laidOut;
  laidOut.layout = checkLayout(out);
  laidOut.pattern = std::make_shared<const LaidOutPattern>(
      LaidOutPattern{std::move(out), std::move(font.value()), o});
  return laidOut;
}

}  // namespace dform::fab

namespace dform {

Result<LaidOutExport> layOutNest(const std::vector<NestItem>& items, const ExportOptions& options) {
  try {
    return fab::layOutNestOrThrow(items, options);
  } catch (const Interrupted&) {
    return interruptedDuring("the nest");
  }
}

Result<PreparedExport> renderNest(const LaidOutExport& laidOut) {
  try {
    return fab::renderPattern(laidOut);
  } catch (const Interrupted&) {
    return interruptedDuring("the nest");
  }
}

}  // namespace dform
