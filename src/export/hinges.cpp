// SPDX-License-Identifier: GPL-3.0-or-later
// Kerf-bending (living-hinge) cuts for a rigid sheet: rows of bridged slits parallel to the body's
// folds, where the solved shape bends. A piece's folds of at least kHingeMinDeg group into
// families of parallel neighbours (the exact body's folds through a piece come in such families);
// each fold's angle is spread over its band (half way to its neighbours), which gives the shape's
// bending radius there (band / angle). Rows then walk across each family, each bending by the
// material's row angle over a cell as wide as that angle times the tightest radius in it (never
// narrower than the material's row pitch): the radius a row allows is its cell over its angle, at
// most the shape's wherever the material can bend that tightly. Rows stay a solid margin inside
// the seam (past the joint holes), clear of holes and free edges, and in their own family's part
// of the piece; slits are staggered between rows and end short of every row's ends, so no cut
// meets another or the edge and the piece stays one part.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "dform/core/polyline.h"
#include "pattern_layout.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

// Folds gentler than this are left to the sheet's own give: no hinge (degrees).
constexpr double kHingeMinDeg = 2.0;
// Folds this close to parallel (degrees) and at most kFamilyGap apart (mm) are one family.
constexpr double kParallelDeg = 0.5, kFamilyGap = 40.0;
// An end fold's band reaches this far at most on its open side (mm).
constexpr double kMaxHalfBand = 20.0;
// The slits: this long, the bridges between them and at a row's ends this wide (mm); a slit
// shorter than kMinSlit is left out.
constexpr double kSlit = 20.0, kBridge = 3.0, kMinSlit = 2.0;
// Rows are clipped to the piece by sampling them this finely (mm), the ends then bisected.
constexpr double kSampleStep = 0.5;
// Slits keep this far from a label's footprint, so no engraved or printed text is cut through.
constexpr double kLabelMargin = 1.0;

struct Fold {
  int index = 0;     // in ExportOptions::folds
  Vec2 a, b;         // flat frame
  double theta = 0;  // radians
};

Vec2 unit(const Fold& f) { return (f.b - f.a).normalized(); }

// Where the normal through fold i's midpoint meets fold j's segment: the signed distance along
// the normal, or nullopt.
std::optional<double> across(const Fold& i, const Fold& j) {
  const Vec2 mid = 0.5 * (i.a + i.b), d = unit(i), n(-d.y(), d.x());
  const Vec2 u = j.b - j.a;
  const double det = n.x() * (-u.y()) - n.y() * (-u.x());
  if (std::abs(det) < 1e-12) return std::nullopt;
  const Vec2 r = j.a - mid;
  const double t = (r.x() * (-u.y()) - r.y() * (-u.x())) / det;
  const double s = (n.x() * r.y() - n.y() * r.x()) / det;
  if (s < 0 || s > 1) return std::nullopt;
  return t;
}

// Families: folds parallel within kParallelDeg whose normals through the midpoint meet each other
// within kFamilyGap, joined transitively.
std::vector<std::vector<int>> families(const std::vector<Fold>& folds) {
  std::vector<int> root(folds.size());
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int i) {
    while (root[size_t(i)] != i) i = root[size_t(i)] = root[size_t(root[size_t(i)])];
    return i;
  };
  const double parallel = std::cos(kParallelDeg * kPi / 180);
  for (size_t i = 0; i < folds.size(); ++i)
    for (size_t j = i + 1; j < folds.size(); ++j) {
      if (std::abs(unit(folds[i]).dot(unit(folds[j]))) < parallel) continue;
      const std::optional<double> t = across(folds[i], folds[j]);
      if (t && std::abs(*t) <= kFamilyGap) root[size_t(find(int(i)))] = find(int(j));
    }
  std::vector<std::vector<int>> out;
  std::vector<int> slot(folds.size(), -1);
  for (size_t i = 0; i < folds.size(); ++i) {
    const int r = find(int(i));
    if (slot[size_t(r)] < 0) {
      slot[size_t(r)] = int(out.size());
      out.emplace_back();
    }
    out[size_t(slot[size_t(r)])].push_back(int(i));
  }
  return out;
}

// A family across its normal: each fold's position and band, the shape's radius on it.
struct Band {
  int fold = 0;
  double at = 0, lo = 0, hi = 0;
  double radius = 0;  // band / angle (mm)
};

std::vector<Band> bands(const std::vector<Fold>& folds, const std::vector<int>& family,
                        const Vec2& n, const std::vector<Fold>& all) {
  std::vector<Band> out;
  for (int f : family) out.push_back({f, n.dot(0.5 * (folds[size_t(f)].a + folds[size_t(f)].b))});
  std::sort(out.begin(), out.end(), [](const Band& x, const Band& y) { return x.at < y.at; });
  // A lone fold's band reaches half way to the nearest other fold on each side (any angle), at
  // most kMaxHalfBand; an end fold's open side mirrors its inner half gap.
  auto openHalf = [&](const Band& b, double side) {
    const Fold& f = folds[size_t(b.fold)];
    const Vec2 d = unit(f);
    const double along = Vec2(-d.y(), d.x()).dot(n) < 0 ? -1.0 : 1.0;  // f's normal against n
    double nearest = 2 * kMaxHalfBand;
    for (const Fold& other : all) {
      if (&other == &f) continue;
      const std::optional<double> t = across(f, other);
      if (t && *t * along * side > 1e-9) nearest = std::min(nearest, std::abs(*t));
    }
    return 0.5 * nearest;
  };
  for (size_t k = 0; k < out.size(); ++k) {
    const double left = k > 0 ? 0.5 * (out[k].at - out[k - 1].at) : -1;
    const double right = k + 1 < out.size() ? 0.5 * (out[k + 1].at - out[k].at) : -1;
    out[k].lo = out[k].at - (left >= 0 ? left : right >= 0 ? right : openHalf(out[k], -1));
    out[k].hi = out[k].at + (right >= 0 ? right : left >= 0 ? left : openHalf(out[k], 1));
    out[k].radius = (out[k].hi - out[k].lo) / folds[size_t(out[k].fold)].theta;
  }
  return out;
}

// The tightest radius the bands need between x0 and x1.
double neededOver(const std::vector<Band>& bands, double x0, double x1) {
  double r = 1e300;
  for (const Band& b : bands)
    if (b.hi > x0 && b.lo < x1) r = std::min(r, b.radius);
  return r;
}

// Where a row of a family may be cut: in the material, the margins clear, off the piece's labels
// (sheet mm, through `place`), and nearer its own family's folds than any other family's.
struct RowRoom {
  const std::vector<Polyline>* material;
  const Polyline* seam;
  std::vector<Polyline> freeEdges, holes;
  double seamMargin = 0, edgeMargin = 0, holeMargin = 0;
  const std::vector<Fold>* folds;
  const std::vector<int>* familyOf;  // per fold
  const Placement* place;
  const std::vector<Polyline>* labels;  // convex footprints
  std::vector<Box> labelBoxes;          // theirs, grown by kLabelMargin
  bool onLabel(const Vec2& q) const {
    const Vec2 s = place->point(q);
    for (size_t k = 0; k < labelBoxes.size(); ++k) {
      const Box& b = labelBoxes[k];
      if (s.x() < b.lo.x() || s.x() > b.hi.x() || s.y() < b.lo.y() || s.y() > b.hi.y()) continue;
      const std::vector<Polyline> hull{(*labels)[k]};
      if (insideRegion(hull, s) || distanceToPolylines(hull, s, true) < kLabelMargin) return true;
    }
    return false;
  }
  bool ok(const Vec2& q, int family) const {
    if (!insideRegion(*material, q) || onLabel(q)) return false;
    if (distanceToPolylines({*seam}, q, true) < seamMargin) return false;
    if (!freeEdges.empty() && distanceToPolylines(freeEdges, q, true) < edgeMargin) return false;
    if (!holes.empty() && distanceToPolylines(holes, q, true) < holeMargin) return false;
    double own = 1e300, other = 1e300;
    for (size_t f = 0; f < folds->size(); ++f) {
      double& nearest = (*familyOf)[f] == family ? own : other;
      nearest = std::min(nearest, distanceToSegment(q, (*folds)[f].a, (*folds)[f].b));
    }
    return own <= other;
  }
};

// The runs of [from, to] where ok(t) holds, sampled every kSampleStep, their ends bisected to
// 0.01 mm.
template <class Ok>
std::vector<std::pair<double, double>> runs(const Ok& ok, double from, double to) {
  std::vector<std::pair<double, double>> out;
  auto edge = [&](double inside, double outside) {
    while (std::abs(outside - inside) > 0.01) {
      const double mid = 0.5 * (inside + outside);
      (ok(mid) ? inside : outside) = mid;
    }
    return inside;
  };
  bool in = false;
  double start = 0, previous = from;
  for (double t = from; t <= to; t += kSampleStep) {
    const bool now = ok(t);
    if (now && !in) start = t == from ? t : edge(t, previous);
    if (!now && in) out.emplace_back(start, edge(previous, t));
    in = now;
    previous = t;
  }
  if (in) out.emplace_back(start, ok(to) ? to : edge(previous, to));
  return out;
}

// The stretches of the line {p : n.p = at} where a row of `family` may be cut, as (t0, t1)
// along d from the point at * n.
std::vector<std::pair<double, double>> stretches(const RowRoom& room, int family, const Vec2& n,
                                                 const Vec2& d, double at, double reach) {
  const Vec2 c = at * n;
  return runs([&](double t) { return room.ok(c + t * d, family); }, -reach, reach);
}

// A row's slits on the stretch (t0, t1): kSlit long, kBridge apart and from either end, the odd
// rows' shifted by half a period so that the links between rows are staggered.
std::vector<std::pair<double, double>> slits(double t0, double t1, int row) {
  std::vector<std::pair<double, double>> out;
  const double a = t0 + kBridge, b = t1 - kBridge, period = kSlit + kBridge;
  if (b - a < kMinSlit) return out;
  const double phase = (row % 2) * 0.5 * period;
  const double first = a + std::fmod(phase, period) - period;
  for (double s = first; s < b; s += period) {
    const double lo = std::max(s, a), hi = std::min(s + kSlit, b);
    if (hi - lo >= kMinSlit) out.emplace_back(lo, hi);
  }
  return out;
}

// Each of a hinge's folds (in `across`' order) against the rows across its band (their cells
// across, in `cells`): the loosest radius the rows with slits allow there, the angle they bend
// there (each row its share of the band), and the fold's stretches in the seam margin.
void foldFigures(const std::vector<Band>& across,
                 const std::vector<std::pair<double, double>>& cells, double rowAngle,
                 const RowRoom& room, const std::vector<Fold>& folds, const Placement& place,
                 HingeInfo& hinge) {
  for (size_t i = 0; i < across.size(); ++i) {
    HingeFoldInfo& info = hinge.folds[i];
    double bend = 0;
    for (size_t r = 0; r < cells.size(); ++r) {
      const double overlap =
          std::min(cells[r].second, across[i].hi) - std::max(cells[r].first, across[i].lo);
      if (hinge.rows[r].cuts.empty() || overlap <= 1e-9) continue;
      info.radiusAllowedMm = std::max(info.radiusAllowedMm, hinge.rows[r].radiusAllowedMm);
      bend += rowAngle * overlap / (cells[r].second - cells[r].first);
    }
    info.bendDeg = bend * 180 / kPi;
    const Fold& f = folds[size_t(across[i].fold)];
    const double length = (f.b - f.a).norm();
    const Vec2 u = (f.b - f.a) / length;
    const std::vector<Polyline> seam{*room.seam};
    const auto inMargin = [&](double t) {
      return distanceToPolylines(seam, f.a + t * u, true) < room.seamMargin;
    };
    for (const auto& [t0, t1] : runs(inMargin, 0.0, length))
      info.inSeamMargin.push_back(place.map(Polyline{f.a + t0 * u, f.a + t1 * u}));
  }
}

}  // namespace

double hingeTurnDeg(const HingeInfo& hinge) {
  double sum = 0;
  for (const HingeFoldInfo& f : hinge.folds) sum += f.angleDeg;
  return sum;
}

double hingeBendDeg(const HingeInfo& hinge) {
  double sum = 0;
  for (const HingeRow& row : hinge.rows)
    if (!row.cuts.empty()) sum += row.pitchMm / row.radiusAllowedMm * 180 / kPi;
  return sum;
}

std::vector<HingeInfo> hingesOf(const ExportOptions& o, int p, const FlatPieces& flat,
                                const std::vector<Polyline>& jointLoops, const JointSettings& joint,
                                const MaterialPreset& material, const Placement& place,
                                double scale, const std::vector<Polyline>& labels) {
  std::vector<HingeInfo> out;
  std::vector<Fold> folds;
  for (size_t i = 0; i < o.folds.size(); ++i) {
    const FoldToScore& f = o.folds[i];
    if (f.piece == p && f.angleDeg >= kHingeMinDeg && (f.to - f.from).norm() > 1e-9)
      folds.push_back({int(i), scale * f.from, scale * f.to, f.angleDeg * kPi / 180});
  }
  if (folds.empty()) return out;
  const std::vector<std::vector<int>> fams = families(folds);
  std::vector<int> familyOf(folds.size());
  for (size_t k = 0; k < fams.size(); ++k)
    for (int f : fams[k]) familyOf[size_t(f)] = int(k);
  const double t = material.thicknessMm;
  RowRoom room;
  room.material = &flat.material[p];
  room.seam = &flat.seams[p].P;
  const std::vector<Polyline>& loops = flat.material[p];
  for (size_t k = 0; k < loops.size(); ++k)
    if (!(loops[k].size() == room.seam->size() &&
          std::equal(loops[k].begin(), loops[k].end(), room.seam->begin())))
      room.freeEdges.push_back(loops[k]);
  room.holes = jointLoops;
  // Solid along the seam past the joint holes (and a sheet's thickness more), along free edges and
  // round holes.
  room.seamMargin =
      joint.joint == Joint::Glue ? std::max(3 * t, 5.0) : joint.edgeMm + 0.5 * joint.diameterMm + t;
  room.edgeMargin = std::max(2 * t, 3.0);
  room.holeMargin = std::max(t, 1.0);
  room.folds = &folds;
  room.familyOf = &familyOf;
  room.place = &place;
  room.labels = &labels;
  for (const Polyline& label : labels) {
    Box b = boxOf({label});
    b.add(b.lo - Vec2(kLabelMargin, kLabelMargin));
    b.add(b.hi + Vec2(kLabelMargin, kLabelMargin));
    room.labelBoxes.push_back(b);
  }
  Box box = boxOf(loops);
  const double reach = (box.hi - box.lo).norm() + 1.0;
  const double rowAngle = material.hingeRowDeg * kPi / 180;
  for (size_t k = 0; k < fams.size(); ++k) {
    const Fold& longest =
        folds[size_t(*std::max_element(fams[k].begin(), fams[k].end(), [&](int x, int y) {
          return (folds[size_t(x)].b - folds[size_t(x)].a).norm() <
                 (folds[size_t(y)].b - folds[size_t(y)].a).norm();
        }))];
    const Vec2 d = unit(longest), n(-d.y(), d.x());
    const std::vector<Band> across = bands(folds, fams[k], n, folds);
    HingeInfo hinge;
    hinge.id = flat.names[p] + "-hinge-" + std::to_string(k + 1);
    hinge.direction = place.vector(d).normalized();
    const double start = across.front().lo;
    for (const Band& b : across) {
      const Fold& f = folds[size_t(b.fold)];
      HingeFoldInfo info;
      info.index = f.index;
      info.line = place.map(Polyline{f.a, f.b});
      info.angleDeg = f.theta * 180 / kPi;
      info.radiusMm = b.radius;
      info.bandFromMm = b.lo - start;
      info.bandToMm = b.hi - start;
      hinge.folds.push_back(std::move(info));
    }
    // Walk across the bands, a row per cell: as wide as the row angle times the tightest radius
    // in it, never narrower than the material's row pitch.
    const double end = across.back().hi;
    std::vector<std::pair<double, double>> cells;  // each row's, across
    int row = 0;
    for (double x = start; x < end - 1e-9; ++row) {
      double cell = std::max(material.hingeRowMm, rowAngle * neededOver(across, x, x + 1e-9));
      cell = std::max(material.hingeRowMm, rowAngle * neededOver(across, x, x + cell));
      HingeRow r;
      r.pitchMm = cell;
      r.radiusAllowedMm = cell / rowAngle;
      r.radiusNeededMm = neededOver(across, x, std::min(x + cell, end));
      r.fromMm = x - start;
      const double at = x + 0.5 * cell;
      for (const auto& [t0, t1] : stretches(room, int(k), n, d, at, reach))
        for (const auto& [s0, s1] : slits(t0, t1, row))
          r.cuts.push_back(place.map(Polyline{at * n + s0 * d, at * n + s1 * d}));
      hinge.rows.push_back(std::move(r));
      cells.emplace_back(x, x + cell);
      x += cell;
    }
    foldFigures(across, cells, rowAngle, room, folds, place, hinge);
    out.push_back(std::move(hinge));
  }
  return out;
}

namespace {

// A warning naming the hinge's folds that need a tighter radius than the material bends to, and
// a note where its rows with slits bend less than its folds turn.
void hingeMessages(const HingeInfo& hinge, const MaterialPreset& material, PatternBuild& out) {
  const double tightest = material.hingeRowMm / (material.hingeRowDeg * kPi / 180);
  std::vector<const HingeFoldInfo*> tooTight;
  for (const HingeFoldInfo& f : hinge.folds)
    if (f.radiusMm < tightest * (1 - 1e-9)) tooTight.push_back(&f);
  if (!tooTight.empty()) {
    std::string folds;
    for (size_t k = 0; k < tooTight.size(); ++k)
      folds += std::string(k == 0                     ? ""
                           : k + 1 == tooTight.size() ? " and "
                                                      : ", ") +
               std::to_string(tooTight[k]->index) + " (" + formatMm(tooTight[k]->radiusMm, 1) +
               " mm)";
    out.warnings.push_back(hinge.id + ": " + material.name + " bends to a radius of " +
                           formatMm(tightest, 1) + " mm at the tightest; the shape needs less at " +
                           (tooTight.size() == 1 ? "fold " : "folds ") + folds +
                           " of report.json's model.folds: the sheet cannot follow it there");
  }
  const double turn = hingeTurnDeg(hinge), bend = hingeBendDeg(hinge);
  if (bend < turn * (1 - 1e-9))
    out.messages.push_back(hinge.id + ": its rows of slits bend " + formatMm(bend, 1) + " of the " +
                           formatMm(turn, 1) +
                           " degrees its folds turn; the rest lies where no slit may go "
                           "(the solid margin along the seam, holes, labels)");
}

}  // namespace

void addHinges(const ExportOptions& o, const FlatPieces& flat,
               const std::vector<Polyline> jointLoops[2], const Placement place[2], double scale,
               DrawingBuilder& b, PatternBuild& out) {
  const std::optional<MaterialPreset> material = materialNamed(out.joint.material);
  if (!material || !(material->hingeRowMm > 0) || !o.hinge.value_or(material->hinge)) return;
  for (int p = 0; p < 2; ++p) {
    PieceInfo& info = out.pieces[size_t(p)];
    std::vector<Polyline> labels;  // the piece's engraved or printed texts
    for (const Path& path : b.engrave().paths)
      if (path.id.rfind(info.name + "-", 0) == 0) labels.push_back(convexHull(path.parts));
    info.hinges =
        hingesOf(o, p, flat, jointLoops[p], out.joint, *material, place[p], scale, labels);
    for (const HingeInfo& hinge : info.hinges) hingeMessages(hinge, *material, out);
  }
  drawHinges(out.pieces, b);
}

void drawHinges(const std::vector<PieceInfo>& pieces, DrawingBuilder& b) {
  for (const PieceInfo& piece : pieces)
    for (const HingeInfo& hinge : piece.hinges)
      for (size_t k = 0; k < hinge.rows.size(); ++k) {
        if (hinge.rows[k].cuts.empty()) continue;
        Path cuts;
        cuts.id = hinge.id + "-row-" + twoDigits(int(k + 1));
        cuts.parts = hinge.rows[k].cuts;
        b.cut().paths.push_back(std::move(cuts));
      }
}

}  // namespace dform::fab
