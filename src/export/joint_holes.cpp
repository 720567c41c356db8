// Joint holes for sheet materials: holes along the seam, a fixed distance inside each piece, at
// matching seam points. With --joint holes, hole k of A and hole k of B mark one point of the 3D
// seam (the seam pair index and fraction, as the ticks do): a cable tie, rivet or stitch through
// the pair closes the seam there. With --joint lace the holes alternate between the pieces along
// the seam, B's halfway between A's, so that a lace zigzags A, B, A, B across the seam: every
// pass crosses it at the same slant and pulls the edges together, edge to edge, with no two
// passes through one hole. Holes keep clear of the seam's corners, where the edges meet at an
// angle and little material surrounds a hole, and of each other.
#include <algorithm>
#include <cmath>

#include "dform/export/pattern_parts.h"
#include "dform/export/plane_geometry.h"

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
// an even count when `even` (lace alternates between the pieces all the way round).
std::vector<double> holeParameters(std::vector<Corner> corners, double L, double pitch,
                                   double diameter, bool even) {
  if (corners.empty()) {
    int n = std::max(2, int(std::ceil(L / pitch - 1e-9)));
    if (even && n % 2) ++n;
    std::vector<double> s;
    for (int k = 0; k < n; ++k) s.push_back(k * L / n);
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

}  // namespace

std::vector<FlatHole> makeJointHoles(const Seam seams[2], const std::vector<Polyline> material[2],
                                     const JointSettings& joint,
                                     std::vector<std::string>& messages) {
  if (joint.joint == Joint::Glue) return {};
  const bool lace = joint.joint == Joint::Lace;
  std::vector<Corner> corners = seamCorners(seams, 0, joint);
  for (const Corner& c : seamCorners(seams, 1, joint)) corners.push_back(c);
  const double L = seams[0].L;
  const std::vector<double> params = holeParameters(
      corners, L, lace ? 0.5 * joint.spacingMm : joint.spacingMm, joint.diameterMm, lace);
  // The holes at each parameter (a pair, or one for lace), then those clear of edges, corners and
  // the holes kept before them.
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
  std::vector<FlatHole> kept;
  int offered = 0, index = 0;
  for (size_t k = 0; k < params.size(); ++k) {
    std::vector<FlatHole> group;
    const int p = int(k % 2);
    if (lace) {
      group.push_back(holeAt(p, reachable(params[k], p, p), int(k)));
    } else {
      const double s = reachable(params[k], 0, 1);
      group = {holeAt(0, s, int(k)), holeAt(1, s, int(k))};
    }
    ++offered;
    bool clear = true;
    for (const FlatHole& h : group) {
      clear = clear && clearOfEdges(h.centre, material[h.piece], corners, h.piece, joint);
      for (const FlatHole& other : kept)
        clear = clear && (other.piece != h.piece ||
                          (other.centre - h.centre).norm() >= 2 * joint.diameterMm);
    }
    if (!clear) continue;
    for (FlatHole& h : group) {
      h.index = lace ? int(k) : index;
      kept.push_back(h);
    }
    ++index;
  }
  const int dropped = offered - (lace ? int(kept.size()) : int(kept.size()) / 2);
  const std::string unit = lace ? "lacing holes" : "hole pairs";
  if (kept.empty())
    messages.push_back("joint holes: none fit along the seam (" + std::to_string(offered) + " " +
                       unit + " tried, each closer than a diameter to a corner or another " +
                       "hole, or too near an edge)");
  else if (dropped > 0)
    messages.push_back("joint holes: " + std::to_string(dropped) + " of " +
                       std::to_string(offered) + " " + unit +
                       " left out: closer than a diameter to a corner or another hole, or too "
                       "near an edge");
  return kept;
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
