#include "export/plane_geometry.h"

#include <algorithm>
#include <cmath>

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

double overlapArea(const Polyline& a, const Polyline& b) {
  ClipperLib::Clipper c;
  c.AddPath(toClip(a), ClipperLib::ptSubject, true);
  c.AddPath(toClip(b), ClipperLib::ptClip, true);
  ClipperLib::Paths result;
  c.Execute(ClipperLib::ctIntersection, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  double area = 0;
  for (const auto& p : result) area += std::abs(ClipperLib::Area(p));
  return area / (kClipScale * kClipScale);
}

bool insidePolygon(const Polyline& poly, const Vec2& q) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double distanceToClosed(const Polyline& poly, const Vec2& q) {
  double best = 1e300;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - q).norm());
  }
  return best;
}

}  // namespace dform::fab
