// SPDX-License-Identifier: GPL-3.0-or-later
#include "crease_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "dform/core/polyline.h"
#include "io_util.h"

namespace dform::io_detail {
namespace {

using Vec2 = Eigen::Vector2d;

/// A point where a crease line is cut: its position along the line (segment index plus the
/// fraction along that segment) and where it is.
struct Cut {
  double at;
  Vec2 point;
};

/// The piece's boundary: its outline and holes.
class PieceBoundary {
 public:
  explicit PieceBoundary(const Shape2& shape) {
    loops_.push_back(&shape.outer.points);
    for (const Outline2& hole : shape.holes) loops_.push_back(&hole.points);
  }

  bool inside(const Vec2& q) const {
    if (!insidePolygon(*loops_[0], q)) return false;
    return std::none_of(loops_.begin() + 1, loops_.end(),
                        [&](const Points2* hole) { return insidePolygon(*hole, q); });
  }

  /// The boundary point nearest to q.
  Vec2 nearest(const Vec2& q) const {
    double best = std::numeric_limits<double>::infinity();
    Vec2 nearest = q;
    forEachEdge([&](const Vec2& a, const Vec2& b) {
      const double d = distanceToSegment(q, a, b);
      if (d >= best) return;
      best = d;
      const Vec2 ab = b - a;
      nearest = a + std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) * ab;
    });
    return nearest;
  }

  /// Every place where the segment [a, b] (segment `index` of a line) touches the boundary.
  void cuts(const Vec2& a, const Vec2& b, int index, std::vector<Cut>& out) const {
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const Vec2 ab = b - a;
    forEachEdge([&](const Vec2& c, const Vec2& d) {
      if ((c.cwiseMax(d).array() < lo.array()).any() || (c.cwiseMin(d).array() > hi.array()).any())
        return;
      if (!segmentsIntersect(a, b, c, d)) return;
      const Vec2 p = segmentsMeetingPoint(a, b, c, d);
      out.push_back({index + std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0), p});
    });
  }

 private:
  template <typename F>
  void forEachEdge(F f) const {
    for (const Points2* loop : loops_)
      for (Eigen::Index i = 0; i < loop->rows(); ++i)
        f(Vec2(loop->row(i)), Vec2(loop->row((i + 1) % loop->rows())));
  }

  std::vector<const Points2*> loops_;
};

/// The part of the line P from cut u to cut v, with those cuts' points as its ends.
Points2 between(const Points2& P, const Cut& u, const Cut& v) {
  std::vector<Vec2> points{u.point};
  for (Eigen::Index i = Eigen::Index(std::floor(u.at)) + 1; double(i) < v.at; ++i)
    points.push_back(P.row(i));
  points.push_back(v.point);
  Points2 part(Eigen::Index(points.size()), 2);
  for (std::size_t k = 0; k < points.size(); ++k) part.row(Eigen::Index(k)) = points[k].transpose();
  return dropRepeatedPoints(part, false);
}

/// Where two crease lines cross away from an end they share, if they do.
std::optional<Vec2> crossingAwayFromEnds(const Points2& P, const Points2& Q) {
  const Vec2 ends[] = {P.row(0), P.row(P.rows() - 1), Q.row(0), Q.row(Q.rows() - 1)};
  for (Eigen::Index i = 0; i + 1 < P.rows(); ++i)
    for (Eigen::Index j = 0; j + 1 < Q.rows(); ++j) {
      const Vec2 a = P.row(i), b = P.row(i + 1), c = Q.row(j), d = Q.row(j + 1);
      if (!segmentsIntersect(a, b, c, d)) continue;
      const Vec2 p = segmentsMeetingPoint(a, b, c, d);
      const bool atSharedEnd = std::any_of(ends, ends + 2, [&](const Vec2& e) {
        return (e - p).norm() <= kSamePointMm &&
               std::any_of(ends + 2, ends + 4,
                           [&](const Vec2& f) { return (f - p).norm() <= kSamePointMm; });
      });
      if (!atSharedEnd) return p;
    }
  return std::nullopt;
}

/// The line with repeated points dropped, or why it is no crease: a bad coordinate, fewer than
/// 2 distinct points, or a crossing of itself.
Result<Points2> simpleLine(const std::string& path, const DrawnLine& line,
                           const OutlineReadOptions& options) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": crease " + line.label + " " + what};
  };
  if (const auto bad = findBadCoordinate(line.points, options.maxCoordinate))
    return fail("has a coordinate that " +
                describeBadCoordinate(line.points(bad->first, bad->second), options.maxCoordinate));
  Points2 P = dropRepeatedPoints(line.points, false);
  if (P.rows() < 2) return fail("has fewer than 2 distinct points");
  if (const auto hit = findSelfIntersection(P, false)) {
    const auto [e, f] = *hit;
    return fail(
        "crosses itself near " +
        fmtPoint(segmentsMeetingPoint(P.row(e), P.row(e + 1), P.row(f), P.row(f + 1)).transpose()) +
        " mm");
  }
  return P;
}

Status noCreasesCross(const std::string& path, const Shape2& shape) {
  for (std::size_t i = 0; i < shape.creases.size(); ++i)
    for (std::size_t j = i + 1; j < shape.creases.size(); ++j)
      if (const auto p = crossingAwayFromEnds(shape.creases[i].points, shape.creases[j].points))
        return Status{ErrorCode::InputInvalid, path + ": creases " + shape.creases[i].label +
                                                   " and " + shape.creases[j].label +
                                                   " cross near " + fmtPoint(p->transpose()) +
                                                   " mm; creases may only meet on the boundary"};
  return Status::ok();
}

}  // namespace

Status checkFittedCreases(const std::string& path, const Shape2& shape,
                          const OutlineReadOptions& options) {
  const PieceBoundary boundary(shape);
  for (const CreaseLine& crease : shape.creases) {
    const DrawnLine line{crease.points, crease.label};
    auto fail = [&](const std::string& what) {
      return Status{ErrorCode::InputInvalid, path + ": crease " + line.label + " " + what};
    };
    Result<Points2> checked = simpleLine(path, line, options);
    if (!checked.isOk()) return checked.status();
    const Points2& P = checked.value();
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
      const Vec2 middle = 0.5 * (P.row(i) + P.row(i + 1)).transpose();
      if (!boundary.inside(middle))
        return fail("leaves the piece near " + fmtPoint(middle.transpose()) +
                    " mm; a crease runs inside the piece from boundary to boundary");
    }
    for (const Eigen::Index end : {Eigen::Index(0), P.rows() - 1}) {
      const Vec2 q = P.row(end);
      const double gap = (boundary.nearest(q) - q).norm();
      if (gap > kCreaseEndSnapMm)
        return fail("ends " + fmt(gap) + " mm inside the piece near " + fmtPoint(q.transpose()) +
                    " mm; a crease runs from boundary to boundary");
    }
  }
  return noCreasesCross(path, shape);
}

Status fitCreases(const std::string& path, const std::vector<DrawnLine>& lines,
                  const OutlineReadOptions& options, Shape2& shape) {
  const PieceBoundary boundary(shape);
  for (const DrawnLine& line : lines) {
    auto fail = [&](const std::string& what) {
      return Status{ErrorCode::InputInvalid, path + ": crease " + line.label + " " + what};
    };
    Result<Points2> checked = simpleLine(path, line, options);
    if (!checked.isOk()) return checked.status();
    const Points2& P = checked.value();

    // Cut the line wherever it meets the boundary; the parts inside the piece are creases.
    std::vector<Cut> cuts{{0.0, P.row(0)}};
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i)
      boundary.cuts(P.row(i), P.row(i + 1), int(i), cuts);
    cuts.push_back({double(P.rows() - 1), P.row(P.rows() - 1)});
    std::sort(cuts.begin() + 1, cuts.end() - 1,
              [](const Cut& u, const Cut& v) { return u.at < v.at; });
    std::vector<Points2> parts;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      Points2 part = between(P, cuts[k], cuts[k + 1]);
      if (part.rows() < 2 || !boundary.inside(resampleOpen(part, 2).row(1).transpose())) continue;
      // A part that reaches an end of the drawn line did not meet the boundary there.
      for (const Eigen::Index end : {Eigen::Index(0), part.rows() - 1}) {
        const bool drawnEnd = end == 0 ? k == 0 : k + 2 == cuts.size();
        if (!drawnEnd) continue;
        const Vec2 q = part.row(end), onBoundary = boundary.nearest(q);
        const double gap = (onBoundary - q).norm();
        if (gap > kCreaseEndSnapMm)
          return fail("ends " + fmt(gap) + " mm inside the piece near " + fmtPoint(q.transpose()) +
                      " mm; a crease runs from boundary to boundary");
        part.row(end) = onBoundary.transpose();
      }
      part = dropRepeatedPoints(part, false);
      if (part.rows() >= 2) parts.push_back(std::move(part));
    }
    if (parts.empty()) return fail("lies outside the piece");
    for (std::size_t k = 0; k < parts.size(); ++k)
      shape.creases.push_back(
          {std::move(parts[k]),
           line.label + (parts.size() > 1 ? " (part " + std::to_string(k + 1) + ")" : "")});
  }

  return noCreasesCross(path, shape);
}

}  // namespace dform::io_detail
