// SPDX-License-Identifier: GPL-3.0-or-later
#include "plane_geometry.h"

#include <algorithm>
#include <cmath>

#include "dform/core/polyline.h"

namespace dform::fab {

ClipperLib::Path toClip(const Polyline& p) {
  ClipperLib::Path out;
  out.reserve(p.size());
  for (const Vec2& q : p)
    out.emplace_back(ClipperLib::cInt(std::llround(q.x() * kClipScale)),
                     ClipperLib::cInt(std::llround(q.y() * kClipScale)));
  if (!ClipperLib::Orientation(out)) ClipperLib::ReversePath(out);
  return out;
}

Polyline fromClip(const ClipperLib::Path& p) {
  Polyline out;
  out.reserve(p.size());
  for (const auto& q : p) out.emplace_back(double(q.X) / kClipScale, double(q.Y) / kClipScale);
  return out;
}

double overlapArea(const std::vector<Polyline>& a, const std::vector<Polyline>& b) {
  ClipperLib::Clipper c;
  for (const Polyline& p : a) c.AddPath(toClip(p), ClipperLib::ptSubject, true);
  for (const Polyline& p : b) c.AddPath(toClip(p), ClipperLib::ptClip, true);
  ClipperLib::Paths result;
  c.Execute(ClipperLib::ctIntersection, result, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  double area = 0;  // holes come back clockwise, with negative area
  for (const auto& p : result) area += ClipperLib::Area(p);
  return std::max(area, 0.0) / (kClipScale * kClipScale);
}

std::vector<Polyline> clipToRegion(const Polyline& line, const std::vector<Polyline>& loops) {
  ClipperLib::Path open;
  for (const Vec2& q : line)
    open.emplace_back(ClipperLib::cInt(std::llround(q.x() * kClipScale)),
                      ClipperLib::cInt(std::llround(q.y() * kClipScale)));
  ClipperLib::Clipper c;
  c.AddPath(open, ClipperLib::ptSubject, false);
  for (const Polyline& p : loops) c.AddPath(toClip(p), ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  ClipperLib::Paths parts;
  ClipperLib::OpenPathsFromPolyTree(tree, parts);
  std::vector<Polyline> out;
  for (const auto& part : parts) {
    Polyline q;
    for (const auto& v : part) q.emplace_back(double(v.X) / kClipScale, double(v.Y) / kClipScale);
    out.push_back(std::move(q));
  }
  return out;
}

double overlapArea(const Polyline& a, const Polyline& b) {
  return overlapArea(std::vector<Polyline>{a}, std::vector<Polyline>{b});
}

bool insideRegion(const std::vector<Polyline>& loops, const Vec2& q) {
  bool inside = false;
  for (const Polyline& loop : loops) inside = inside != insidePolygon(loop, q);
  return inside;
}

double distanceToPolylines(const std::vector<Polyline>& lines, const Vec2& q, bool closed) {
  double best = 1e300;
  for (const Polyline& line : lines)
    for (size_t i = 0; i + (closed ? 0 : 1) < line.size(); ++i)
      best = std::min(best, distanceToSegment(q, line[i], line[(i + 1) % line.size()]));
  return best;
}

bool overlapsAny(const Polyline& shape, const std::vector<Polyline>& others, double tol) {
  const Box box = boxOf({shape});
  return std::any_of(others.begin(), others.end(), [&](const Polyline& other) {
    return box.overlaps(boxOf({other})) && overlapArea(shape, other) > tol;
  });
}

BoxIndex::Span BoxIndex::span(const Box& box) const {
  auto at = [&](double x) { return long(std::floor(x / cell_)); };
  return {at(box.lo.x()), at(box.lo.y()), at(box.hi.x()), at(box.hi.y())};
}

namespace {
// x in the high 32 bits, y in the low ones; shifted as unsigned, since shifting a negative
// signed value is undefined behaviour (cells left of or below the origin have negative indices).
long long cellKey(long x, long y) {
  return static_cast<long long>((static_cast<unsigned long long>(x) << 32) ^
                                (static_cast<unsigned long long>(y) & 0xffffffffULL));
}
}  // namespace

void BoxIndex::insert(int id, const Box& box) {
  if (boxes_.size() <= size_t(id)) boxes_.resize(size_t(id) + 1);
  boxes_[size_t(id)] = box;
  const Span s = span(box);
  if (s.x1 - s.x0 >= kMaxCellsPerAxis || s.y1 - s.y0 >= kMaxCellsPerAxis) {
    large_.push_back(id);
    return;
  }
  for (long x = s.x0; x <= s.x1; ++x)
    for (long y = s.y0; y <= s.y1; ++y) cells_[cellKey(x, y)].push_back(id);
}

std::vector<int> BoxIndex::overlapping(const Box& box) const {
  std::vector<int> found = large_;
  const Span s = span(box);
  // A query larger than the grid would visit many empty cells: every filed box is a candidate.
  if (s.x1 - s.x0 >= kMaxCellsPerAxis || s.y1 - s.y0 >= kMaxCellsPerAxis) {
    found.clear();
    for (size_t id = 0; id < boxes_.size(); ++id) found.push_back(int(id));
  } else {
    for (long x = s.x0; x <= s.x1; ++x)
      for (long y = s.y0; y <= s.y1; ++y) {
        const auto it = cells_.find(cellKey(x, y));
        if (it != cells_.end()) found.insert(found.end(), it->second.begin(), it->second.end());
      }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  found.erase(std::remove_if(found.begin(), found.end(),
                             [&](int id) { return !boxes_[size_t(id)].overlaps(box); }),
              found.end());
  return found;
}

Polyline convexHull(const std::vector<Polyline>& parts) {
  Polyline pts;
  for (const Polyline& part : parts) pts.insert(pts.end(), part.begin(), part.end());
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (pts.size() < 3) return pts;
  auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  Polyline hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

Vec2 pointAlong(const Polyline& line, double s, Vec2* tangent) {
  double acc = 0;
  Vec2 dir(1, 0);
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double seg = (line[i + 1] - line[i]).norm();
    if (seg <= 0) continue;
    dir = (line[i + 1] - line[i]) / seg;
    if (acc + seg >= s) {
      if (tangent) *tangent = dir;
      return line[i] + (s - acc) * dir;
    }
    acc += seg;
  }
  if (tangent) *tangent = dir;
  return line.back();
}

}  // namespace dform::fab
