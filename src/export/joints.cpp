// SPDX-License-Identifier: GPL-3.0-or-later
// Joints for sheet materials along the seam, at matching seam points of both pieces.
// With --joint holes, hole k of A and hole k of B mark one point of the 3D seam (the seam pair
// index and fraction, as the ticks do): a cable tie, rivet or stitch through the pair closes the
// seam there. With --joint lace the holes alternate between the pieces along the seam, B's
// halfway between A's, so that a lace zigzags A, B, A, B across the seam: every pass crosses it
// at the same slant and pulls the edges together, edge to edge, with no two passes through one
// hole. With --joint slots, joint k is a tongue growing out of A's seam and a slot in B the edge
// distance inside B's seam at the same seam point: zipped, the tongue folds back along the seam,
// lies against B and passes through the slot, its barbed head holding it there. A tongue needs
// both seams straight along it (it lies flat against B only where neither bends away from its
// chord); where a seam bends more, or a tongue or slot has no room, the joint is a hole pair.
// Joints keep clear of the seam's corners, where the edges meet at an angle and little material
// surrounds them, and of each other.
#include <algorithm>
#include <cmath>
#include <optional>

#include "pattern_parts.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

// A seam vertex turning by at least this much is a corner (a square's corner turns 90 degrees; a
// smooth seam of a few dozen points turns a few degrees at each).
constexpr double kCornerTurnDeg = 35;

// The turn of the seam at vertex i towards its material (positive where the vertex is convex).
double turnTowardsMaterial(const Seam& seam, int i) {
  const Vec2 a = seam.dir((i - 1 + seam.n()) % seam.n()), b = seam.dir(i);
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)) * seam.orient * (seam.hole ? -1 : 1);
}

// A little more than `mm`: past a limit where a hole would be exactly as near two segments (a
// tie in which is its nearest seam point) or exactly a diameter from a hole.
double withMargin(double mm) { return 1.05 * mm + 0.005; }

struct Corner {
  double s = 0;  // seam parameter (A's arc length)
  Vec2 at;       // the corner in its piece's flat frame
  int piece = 0;
  double clear = 0;  // seam length a hole keeps from it
};

// The corners of piece p's seam, with the seam length a hole keeps from each: a gap of one
// diameter to the corner point; at a corner turning towards the material (convex, interior angle
// phi) the holes either side, both `edge` inside, converge: each keeps a diameter's gap to its
// neighbour across the corner (half the distance between them, a sin(phi/2) - edge cos(phi/2),
// at least a diameter), which also keeps it the edge distance from the other side.
std::vector<Corner> seamCorners(const Seam seams[2], int p, const JointSettings& j) {
  const Seam& seam = seams[p];
  std::vector<Corner> corners;
  for (int i = 0; i < seam.n(); ++i) {
    const double turn = turnTowardsMaterial(seam, i);
    if (std::abs(turn) < kCornerTurnDeg * kPi / 180) continue;
    double clear = 1.5 * j.diameterMm;
    if (turn > 0) {
      const double halfPhi = 0.5 * (kPi - std::min(turn, 150 * kPi / 180));
      clear = std::max(
          clear, withMargin((j.diameterMm + j.edgeMm * std::cos(halfPhi)) / std::sin(halfPhi)));
    }
    const double own = seam.cum[size_t(i)];
    corners.push_back(
        {p == 0 ? own : matchingArc(seams[1], seams[0], own), seam.P[size_t(i)], p, clear});
  }
  return corners;
}

// Evenly spaced seam parameters at most `pitch` apart between the corners, `clear` from each;
// an even count when `even` (lace alternates between the pieces all the way round). Without
// corners the first is at `phase` pitches from the seam's start.
std::vector<double> holeParameters(std::vector<Corner> corners, double L, double pitch,
                                   double diameter, bool even, double phase) {
  if (corners.empty()) {
    int n = std::max(2, int(std::ceil(L / pitch - 1e-9)));
    if (even && n % 2) ++n;
    std::vector<double> s;
    for (int k = 0; k < n; ++k) s.push_back((k + phase) * L / n);
    return s;
  }
  std::sort(corners.begin(), corners.end(),
            [](const Corner& a, const Corner& b) { return a.s < b.s; });
  // A corner of both pieces (the same seam point) keeps the larger clearance of the two.
  std::vector<Corner> merged;
  for (const Corner& c : corners)
    if (!merged.empty() && c.s - merged.back().s < 1e-6)
      merged.back().clear = std::max(merged.back().clear, c.clear);
    else
      merged.push_back(c);
  if (merged.size() > 1 && merged.front().s + L - merged.back().s < 1e-6) {
    merged.front().clear = std::max(merged.front().clear, merged.back().clear);
    merged.pop_back();
  }
  corners = std::move(merged);
  // Each stretch between neighbouring corners: its free part [from, to] and its hole count.
  struct Stretch {
    double from, to;
    int n;
  };
  std::vector<Stretch> stretches;
  int total = 0;
  for (size_t k = 0; k < corners.size(); ++k) {
    const Corner& c0 = corners[k];
    const Corner& c1 = corners[(k + 1) % corners.size()];
    const double end = k + 1 < corners.size() ? c1.s : c1.s + L;
    Stretch st{c0.s + c0.clear, end - c1.clear, 0};
    const double room = st.to - st.from;
    st.n = room < 0 ? 0 : room < 2 * diameter ? 1 : int(std::ceil(room / pitch - 1e-9)) + 1;
    total += st.n;
    stretches.push_back(st);
  }
  if (even && total % 2) {  // one hole more where there is most room
    Stretch* roomiest = &stretches.front();
    for (Stretch& st : stretches)
      if (st.to - st.from > roomiest->to - roomiest->from) roomiest = &st;
    ++roomiest->n;
  }
  std::vector<double> s;
  for (const Stretch& st : stretches)
    for (int k = 0; k < st.n; ++k) {
      const double t =
          st.n == 1 ? 0.5 * (st.from + st.to) : st.from + k * (st.to - st.from) / (st.n - 1);
      s.push_back(std::fmod(t, L));
    }
  std::sort(s.begin(), s.end());
  return s;
}

// The seam point nearest to `own` (arc length along `seam`) whose inward normal at `edge` mm
// ends at a point that has it as its nearest seam point: next to a convex vertex turning by t,
// the inward normals of the seam within edge * tan(t / 2) of it end nearer the other side.
double reachableArc(const Seam& seam, double own, double edge) {
  const int i = seam.segmentAt(own);
  const double start = seam.cum[size_t(i)], end = seam.cum[size_t(i) + 1];
  own = std::clamp(own, start, end);
  auto lost = [&](int v) {
    const double t = turnTowardsMaterial(seam, v % seam.n());
    return t > 0 ? withMargin(edge * std::tan(std::min(t, 3.0) / 2)) : 0.0;
  };
  const double lo = start + lost(i), hi = end - lost(i + 1);
  if (lo > hi) return 0.5 * (start + end);  // a segment too short: its middle
  return std::clamp(own, lo, hi);
}

// Whether a hole at `centre` on piece p keeps the edge distance from every edge (so that its
// nearest seam point is the one it was placed at) and a diameter from every corner of that piece.
bool clearOfEdges(const Vec2& centre, const std::vector<Polyline>& material,
                  const std::vector<Corner>& corners, int p, const JointSettings& j) {
  if (distanceToPolylines(material, centre, true) < j.edgeMm - 1e-6 ||
      !insideRegion(material, centre))
    return false;
  for (const Corner& c : corners)
    if (c.piece == p && (c.at - centre).norm() < 1.5 * j.diameterMm) return false;
  return true;
}

// The largest distance of `line`'s points from the chord between its ends (mm).
double chordDeviation(const Polyline& line) {
  const Vec2 a = line.front(), d = line.back() - a;
  const double len = d.norm();
  double most = 0;
  for (const Vec2& q : line) {
    const Vec2 r = q - a;
    most = std::max(most, len > 0 ? std::abs(d.x() * r.y() - d.y() * r.x()) / len : r.norm());
  }
  return most;
}

// Over a tongue's width each seam stays this close to its chord: the tongue, a straight strip
// folded on A's seam, then lies flat against B and enters B's straight slot; 0.25 mm is half a
// slot's width in card.
constexpr double kSlotStraightMm = 0.25;
// What a slot is longer than its tongue at either end (mm), for the tongue to slide in.
constexpr double kSlotEndPlayMm = 0.2;

// The tongue on A and the slot in B of the joint whose slot's seam point is seam parameter s, or
// nullopt where the tongue would cross the seam's start or either seam strays from its chord.
// The tongue (fold line first) is a neck from the fold to just past the slot, (edge + width / 2
// + thickness), then a head `edge` long (at least 3 mm) whose barbs stand out a tenth of the
// tongue's width (at most 1 mm; none in sheets 1 mm or thicker, which do not flex through the
// slot) and whose tip is chamfered to find the slot.
std::optional<std::pair<FlatTab, FlatSlot>> tongueAndSlot(const Seam seams[2], double s,
                                                          const JointSettings& j) {
  const Seam &a = seams[0], &b = seams[1];
  const double w = j.slotLengthMm, s0 = s - 0.5 * w, s1 = s + 0.5 * w;
  if (s0 < 0 || s1 > a.L) return std::nullopt;
  const double b0 = matchingArc(a, b, s0), b1 = matchingArc(a, b, s1), own = matchingArc(a, b, s);
  if (chordDeviation(a.sub(s0, s1)) > kSlotStraightMm ||
      chordDeviation(b.sub(b0, b1)) > kSlotStraightMm)
    return std::nullopt;
  FlatTab tongue;
  tongue.piece = 0;
  tongue.s0 = tongue.own0 = s0;
  tongue.s1 = tongue.own1 = s1;
  tongue.fold = a.sub(s0, s1);
  const Vec2 a0 = tongue.fold.front(), a1 = tongue.fold.back();
  const Vec2 t = (a1 - a0).normalized(), n = a.outwardOf(t);
  const double thickness = j.thicknessMm > 0 ? j.thicknessMm : 0.3;
  const double neck = j.edgeMm + 0.5 * j.slotWidthMm + thickness, head = std::max(j.edgeMm, 3.0);
  const double barb = thickness < 1 ? std::min(0.1 * w, 1.0) : 0.0;
  const double chamfer = std::min(0.25 * w, 0.5 * head);
  tongue.width = neck + head;
  tongue.polygon = tongue.fold;
  const Vec2 tip = (neck + head) * n;
  // Shoulder, barb, tip, barb, shoulder; without barbs a shoulder is one point (a repeated vertex
  // would read as the outline touching itself).
  tongue.polygon.push_back(a1 + neck * n);
  if (barb > 0) tongue.polygon.push_back(a1 + barb * t + neck * n);
  tongue.polygon.push_back(a1 - chamfer * t + tip);
  tongue.polygon.push_back(a0 + chamfer * t + tip);
  if (barb > 0) tongue.polygon.push_back(a0 - barb * t + neck * n);
  tongue.polygon.push_back(a0 + neck * n);
  tongue.box = boxOf({tongue.polygon});
  int seg = 0;
  const Vec2 foot = b.at(own, &seg);
  FlatSlot slot;
  slot.s = s;
  slot.centre = foot - j.edgeMm * b.outward(seg);
  slot.length = (a1 - a0).norm() + 2 * kSlotEndPlayMm;  // the tongue's neck, to slide through
  slot.width = j.slotWidthMm;
  const Vec2 tb = (b.at(b1) - b.at(b0)).normalized(), nb = b.outwardOf(tb);
  const Vec2 along = 0.5 * slot.length * tb, across = 0.5 * slot.width * nb;
  slot.loop = {slot.centre - along - across, slot.centre - along + across,
               slot.centre + along + across, slot.centre + along - across};
  if (signedArea(toPoints(slot.loop)) > 0) std::reverse(slot.loop.begin(), slot.loop.end());
  return std::make_pair(std::move(tongue), std::move(slot));
}

// The joints kept so far, and the clearance tests a new one must pass against them and the
// pieces: a hole or slot keeps a diameter from every other hole or slot of its piece (edge to
// edge) and from the seam's corners, and its edge distance (a slot: up to the seams' allowed
// bend) from every edge of its piece; a tongue shares no area with A nor with another tongue.
class JointSet {
 public:
  JointSet(const std::vector<Polyline> material[2], const std::vector<Corner>& corners,
           const JointSettings& j)
      : material_(material), corners_(corners), j_(j) {}
  const FlatJoints& joints() const { return joints_; }

  bool holeFits(const FlatHole& h) const {
    if (!clearOfEdges(h.centre, material_[h.piece], corners_, h.piece, j_)) return false;
    for (const FlatHole& other : joints_.holes)
      if (other.piece == h.piece && (other.centre - h.centre).norm() < 2 * j_.diameterMm)
        return false;
    for (const FlatSlot& slot : joints_.slots)
      if (crowds(h, slot)) return false;
    return true;
  }
  bool slotFits(const FlatTab& tongue, const FlatSlot& slot) const {
    if (findSelfIntersection(toPoints(tongue.polygon)) ||
        overlapArea({tongue.polygon}, material_[0]) > kOverlapTolMm2)
      return false;
    for (const FlatTab& other : joints_.tongues)
      if (overlapArea(tongue.polygon, other.polygon) > kOverlapTolMm2) return false;
    const double edge = j_.edgeMm - 0.5 * slot.width - kSlotStraightMm - 1e-6;
    for (const Vec2& q : slot.loop)
      if (!insideRegion(material_[1], q) || distanceToPolylines(material_[1], q, true) < edge)
        return false;
    for (const Corner& c : corners_)
      if (c.piece == 1 && distanceToPolylines({slot.loop}, c.at, true) < j_.diameterMm)
        return false;
    for (const FlatHole& h : joints_.holes)
      if (crowds(h, slot)) return false;
    for (const FlatSlot& other : joints_.slots)
      for (const Vec2& q : slot.loop)
        if (insideRegion({other.loop}, q) ||
            distanceToPolylines({other.loop}, q, true) < j_.diameterMm)
          return false;
    return true;
  }
  void addHole(const FlatHole& h) { joints_.holes.push_back(h); }
  void addSlot(const FlatTab& tongue, const FlatSlot& slot) {
    joints_.tongues.push_back(tongue);
    joints_.slots.push_back(slot);
  }

 private:
  // Whether hole h (on B) comes within a diameter of the slot, edge to edge.
  bool crowds(const FlatHole& h, const FlatSlot& slot) const {
    return h.piece == 1 && distanceToPolylines({slot.loop}, h.centre, true) < 1.5 * j_.diameterMm;
  }

  const std::vector<Polyline>* material_;
  const std::vector<Corner>& corners_;
  const JointSettings& j_;
  FlatJoints joints_;
};

}  // namespace

FlatJoints makeJoints(const Seam seams[2], const std::vector<Polyline> material[2],
                      const JointSettings& joint, std::vector<std::string>& messages) {
  if (joint.joint == Joint::Glue) return {};
  const bool lace = joint.joint == Joint::Lace, slots = joint.joint == Joint::Slots;
  std::vector<Corner> corners = seamCorners(seams, 0, joint);
  for (const Corner& c : seamCorners(seams, 1, joint)) corners.push_back(c);
  // Holes are placed clear of the corners; tongues keep half their width more.
  std::vector<Corner> spread = corners;
  if (slots)
    for (Corner& c : spread) c.clear += 0.5 * joint.slotLengthMm;
  const double L = seams[0].L;
  const std::vector<double> params =
      holeParameters(spread, L, lace ? 0.5 * joint.spacingMm : joint.spacingMm, joint.diameterMm,
                     lace, slots ? 0.5 : 0.0);
  // The seam parameter moved off the stretches no hole centre reaches on the pieces it is for
  // (a few hundredths of a mm next to a smooth seam's vertices), then the hole on piece p there.
  auto reachable = [&](double s, int p0, int p1) {
    for (int round = 0; round < 3; ++round)
      for (int p = p0; p <= p1; ++p) {
        const double own = p == 0 ? s : matchingArc(seams[0], seams[1], s);
        const double moved = reachableArc(seams[p], own, joint.edgeMm);
        if (moved != own) s = p == 0 ? moved : matchingArc(seams[1], seams[0], moved);
      }
    return s;
  };
  auto holeAt = [&](int p, double s, int index) {
    const Seam& seam = seams[p];
    const double own = p == 0 ? s : matchingArc(seams[0], seams[1], s);
    const int seg = std::min(seam.segmentAt(own), seam.n() - 1);
    const Vec2 foot = seam.at(own);
    return FlatHole{p, index, s, own, foot - joint.edgeMm * seam.outward(seg), joint.diameterMm};
  };
  JointSet kept(material, corners, joint);
  int index = 0;
  for (size_t k = 0; k < params.size(); ++k) {
    if (slots) {
      const double s = reachable(params[k], 1, 1);
      if (const auto made = tongueAndSlot(seams, s, joint);
          made && kept.slotFits(made->first, made->second)) {
        FlatSlot slot = made->second;
        slot.index = index++;
        kept.addSlot(made->first, slot);
        continue;
      }
    }
    std::vector<FlatHole> group;
    const int p = int(k % 2);
    if (lace) {
      group.push_back(holeAt(p, reachable(params[k], p, p), int(k)));
    } else {
      const double s = reachable(params[k], 0, 1);
      group = {holeAt(0, s, index), holeAt(1, s, index)};
    }
    if (!std::all_of(group.begin(), group.end(),
                     [&](const FlatHole& h) { return kept.holeFits(h); }))
      continue;
    for (const FlatHole& h : group) kept.addHole(h);
    ++index;
  }
  FlatJoints out = kept.joints();
  const int offered = int(params.size());
  const int made =
      int(out.slots.size()) + (lace ? int(out.holes.size()) : int(out.holes.size()) / 2);
  const std::string unit = slots ? "joints" : lace ? "lacing holes" : "hole pairs";
  if (made == 0)
    messages.push_back("joint holes: none fit along the seam (" + std::to_string(offered) + " " +
                       unit + " tried, each closer than a diameter to a corner or another " +
                       "hole, or too near an edge)");
  else if (made < offered)
    messages.push_back("joint holes: " + std::to_string(offered - made) + " of " +
                       std::to_string(offered) + " " + unit +
                       " left out: closer than a diameter to a corner or another hole, or too "
                       "near an edge");
  if (const int pairs = int(out.holes.size()) / 2; slots && pairs > 0)
    messages.push_back("joint slots: " + std::to_string(pairs) + " of " + std::to_string(offered) +
                       " joints are hole pairs, where a seam bends more than " +
                       formatMm(kSlotStraightMm, 2) + " mm from straight along a " +
                       formatMm(joint.slotLengthMm) + " mm tongue or the tongue has no room");
  return out;
}

Polyline holeLoop(const FlatHole& hole) {
  const double r = 0.5 * hole.diameter;
  // Chords within 5 um of the circle (the kerf offset's tolerance), at least 12.
  const int n = std::max(12, int(std::ceil(kPi / std::acos(std::max(0.0, 1 - 0.005 / r)))));
  Polyline loop;
  for (int k = 0; k < n; ++k) {
    const double a = -2 * kPi * k / n;  // clockwise: a hole in the material
    loop.push_back(hole.centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return loop;
}

}  // namespace dform::fab
