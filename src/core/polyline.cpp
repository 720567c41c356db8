// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/polyline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <vector>

namespace dform {

double closedLength(const Eigen::MatrixXd& P) {
  const Eigen::Index n = P.rows();
  double length = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) length += (P.row((i + 1) % n) - P.row(i)).norm();
  return length;
}

Eigen::VectorXd cumulativeArcLength(const Eigen::MatrixXd& P) {
  const Eigen::Index n = P.rows();
  Eigen::VectorXd s(n);
  if (n == 0) return s;
  s(0) = 0.0;
  for (Eigen::Index i = 1; i < n; ++i) s(i) = s(i - 1) + (P.row(i) - P.row(i - 1)).norm();
  return s;
}

double signedArea(const Points2& P) {
  const Eigen::Index n = P.rows();
  double twiceArea = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    twiceArea += P(i, 0) * P(j, 1) - P(j, 0) * P(i, 1);
  }
  return 0.5 * twiceArea;
}

Eigen::MatrixXd resampleAtFractions(const Eigen::MatrixXd& P,
                                    const std::vector<double>& fractions) {
  assert(P.rows() >= 2 && "resampleAtFractions needs a polyline");
  const Eigen::Index m = P.rows();
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = s(m - 1) + (P.row(0) - P.row(m - 1)).norm();
  Eigen::MatrixXd out(fractions.size(), P.cols());
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    double f = std::fmod(fractions[k], 1.0);
    if (f < 0.0) f += 1.0;
    const double target = f * total;
    // Segment seg runs from row seg to row seg+1 (mod m): the last s(seg) <= target.
    const Eigen::Index seg =
        std::max<Eigen::Index>(0, std::upper_bound(s.data(), s.data() + m, target) - s.data() - 1);
    const double segStart = s(seg);
    const double segLength = (seg + 1 < m ? s(seg + 1) : total) - segStart;
    const double t = segLength > 0.0 ? std::clamp((target - segStart) / segLength, 0.0, 1.0) : 0.0;
    out.row(Eigen::Index(k)) = (1.0 - t) * P.row(seg) + t * P.row((seg + 1) % m);
  }
  return out;
}

Eigen::MatrixXd resampleClosed(const Eigen::MatrixXd& P, int n, double startFraction) {
  assert(n >= 1 && "resampleClosed needs a positive count");
  std::vector<double> fractions(n);
  for (int k = 0; k < n; ++k) fractions[k] = startFraction + double(k) / n;
  return resampleAtFractions(P, fractions);
}

double openLength(const Eigen::MatrixXd& P) {
  return P.rows() < 2 ? 0.0 : cumulativeArcLength(P)(P.rows() - 1);
}

Eigen::MatrixXd resampleOpen(const Eigen::MatrixXd& P, int segments) {
  assert(P.rows() >= 2 && segments >= 1 && "resampleOpen needs a polyline and a segment count");
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = s(P.rows() - 1);
  Eigen::MatrixXd out(segments + 1, P.cols());
  Eigen::Index seg = 0;
  for (int k = 0; k <= segments; ++k) {
    const double target = total * double(k) / segments;
    while (seg + 2 < P.rows() && s(seg + 1) <= target) ++seg;
    const double length = s(seg + 1) - s(seg);
    const double t = length > 0.0 ? std::clamp((target - s(seg)) / length, 0.0, 1.0) : 0.0;
    out.row(k) = (1.0 - t) * P.row(seg) + t * P.row(seg + 1);
  }
  out.row(0) = P.row(0);  // exactly, not up to rounding
  out.row(segments) = P.row(P.rows() - 1);
  return out;
}

Eigen::VectorXd turningAngles(const Eigen::MatrixXd& P) {
  const Eigen::Index n = P.rows();
  Eigen::VectorXd turn = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n && n >= 3; ++k) {
    const Eigen::VectorXd in = (P.row(k) - P.row((k + n - 1) % n)).transpose();
    const Eigen::VectorXd out = (P.row((k + 1) % n) - P.row(k)).transpose();
    const double lengths = in.norm() * out.norm();
    if (lengths > 0.0) turn[k] = std::acos(std::clamp(in.dot(out) / lengths, -1.0, 1.0));
  }
  return turn;
}

std::vector<bool> sampledCorners(const Eigen::MatrixXd& P) {
  const Eigen::Index n = P.rows();
  const Eigen::VectorXd turn = turningAngles(P);
  std::vector<bool> corner(std::size_t(n), false);
  for (Eigen::Index k = 0; k < n; ++k)
    corner[std::size_t(k)] = turn[k] >= kCornerTurnRadians &&
                             turn[k] >= 2.0 * std::max(turn[(k + n - 1) % n], turn[(k + 1) % n]);
  return corner;
}

Eigen::MatrixXd compensateChordLoss(const Eigen::MatrixXd& P) {
  const Eigen::Index n = P.rows();
  Eigen::MatrixXd out = P;
  const Eigen::VectorXd turn = turningAngles(P);
  const std::vector<bool> corner = sampledCorners(P);
  for (Eigen::Index k = 0; k < n && n >= 3; ++k) {
    const Eigen::VectorXd a = (P.row((k + n - 1) % n) - P.row(k)).transpose();
    const Eigen::VectorXd b = (P.row((k + 1) % n) - P.row(k)).transpose();
    if (corner[std::size_t(k)] || a.norm() == 0.0 || b.norm() == 0.0) continue;
    // Circumscribed circle of the three points: kappa = 2 sin(turn) / |a - b|; the centre lies
    // along the bisector a/|a| + b/|b|.
    const double la = a.norm(), lb = b.norm();
    const double kappa = 2.0 * std::sin(turn[k]) / (a - b).norm();
    const Eigen::VectorXd towardCentre = a / la + b / lb;
    if (kappa == 0.0 || towardCentre.norm() == 0.0) continue;
    const double h = 0.5 * (la + lb);
    out.row(k) -= (kappa * h * h / 24.0) * towardCentre.normalized().transpose();
  }
  return out;
}

std::vector<double> cornerFractions(const Points2& P, double minTurnRadians) {
  const Eigen::Index n = P.rows();
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = closedLength(P);
  std::vector<double> corners;
  for (Eigen::Index i = 0; i < n && total > 0.0; ++i) {
    const Eigen::Vector2d in = P.row(i) - P.row((i + n - 1) % n);
    const Eigen::Vector2d out = P.row((i + 1) % n) - P.row(i);
    const double turn = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
    if (std::abs(turn) >= minTurnRadians) corners.push_back(s(i) / total);
  }
  return corners;
}

double nearestArcFraction(const Points2& P, const Eigen::Vector2d& q) {
  const Eigen::Index n = P.rows();
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = closedLength(P);
  double best = std::numeric_limits<double>::infinity();
  double bestArc = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d a = P.row(i), b = P.row((i + 1) % n);
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - q).squaredNorm();
    if (d < best) {
      best = d;
      bestArc = s(i) + t * std::sqrt(len2);
    }
  }
  return total > 0.0 ? std::fmod(bestArc / total, 1.0) : 0.0;
}

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

}  // namespace

bool segmentsIntersect(const Eigen::Vector2d& a0, const Eigen::Vector2d& b0,
                       const Eigen::Vector2d& c0, const Eigen::Vector2d& d0) {
  // Each segment's ends in lexicographic order: where rounding decides a near-touch, the answer
  // must not depend on the direction the segments are walked, or a polygon and its reverse
  // (an outline before and after it is made counter-clockwise) would disagree.
  auto lexLess = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  };
  const Eigen::Vector2d& a = lexLess(b0, a0) ? b0 : a0;
  const Eigen::Vector2d& b = lexLess(b0, a0) ? a0 : b0;
  const Eigen::Vector2d& c = lexLess(d0, c0) ? d0 : c0;
  const Eigen::Vector2d& d = lexLess(d0, c0) ? c0 : d0;
  const double d1 = cross(c, d, a), d2 = cross(c, d, b);
  const double d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && onSegment(c, d, a)) || (d2 == 0 && onSegment(c, d, b)) ||
         (d3 == 0 && onSegment(a, b, c)) || (d4 == 0 && onSegment(a, b, d));
}

namespace {

// The x-range of edge e of the closed polygon P (edge e joins row e to row e+1).
std::pair<double, double> edgeRangeX(const Points2& P, int e) {
  const double x0 = P(e, 0), x1 = P((e + 1) % P.rows(), 0);
  return {std::min(x0, x1), std::max(x0, x1)};
}

// Sweep over x: visits each pair of items whose x-ranges overlap, in sweep order, until `visit`
// returns true.
template <class Visit>
void sweepOverlapping(const std::vector<std::pair<double, double>>& ranges, Visit visit) {
  std::vector<int> order(ranges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return ranges[a].first < ranges[b].first; });
  for (size_t oi = 0; oi < order.size(); ++oi)
    for (size_t oj = oi + 1;
         oj < order.size() && ranges[order[oj]].first <= ranges[order[oi]].second; ++oj)
      if (visit(order[oi], order[oj])) return;
}

}  // namespace

std::optional<std::pair<int, int>> findSelfIntersection(const Points2& P, bool closed) {
  const int n = int(P.rows());
  const int edges = closed ? n : n - 1;
  if (edges < 3) return std::nullopt;
  std::vector<std::pair<double, double>> ranges;
  for (int e = 0; e < edges; ++e) ranges.push_back(edgeRangeX(P, e));
  std::optional<std::pair<int, int>> found;
  sweepOverlapping(ranges, [&](int e, int f) {
    const int gap = std::abs(e - f);
    // Neighbours share a vertex by construction (the first and last edge only when closed).
    if (gap == 1 || (closed && gap == n - 1)) return false;
    if (!segmentsIntersect(P.row(e), P.row((e + 1) % n), P.row(f), P.row((f + 1) % n)))
      return false;
    found = std::make_pair(std::min(e, f), std::max(e, f));
    return true;
  });
  return found;
}

std::optional<std::pair<int, int>> findCrossing(const Points2& P, const Points2& Q) {
  const int n = int(P.rows()), m = int(Q.rows());
  std::vector<std::pair<double, double>> ranges;  // P's edges, then Q's
  for (int e = 0; e < n; ++e) ranges.push_back(edgeRangeX(P, e));
  for (int e = 0; e < m; ++e) ranges.push_back(edgeRangeX(Q, e));
  std::optional<std::pair<int, int>> found;
  sweepOverlapping(ranges, [&](int e, int f) {
    if ((e < n) == (f < n)) return false;  // two edges of the same polygon
    const int i = std::min(e, f), j = std::max(e, f) - n;
    if (!segmentsIntersect(P.row(i), P.row((i + 1) % n), Q.row(j), Q.row((j + 1) % m)))
      return false;
    found = std::make_pair(i, j);
    return true;
  });
  return found;
}

Eigen::Vector2d segmentsMeetingPoint(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                     const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const Eigen::Vector2d r = b - a, s = d - c;
  const double denom = r.x() * s.y() - r.y() * s.x();
  if (denom != 0.0) {
    const double t = ((c - a).x() * s.y() - (c - a).y() * s.x()) / denom;
    if (t >= 0.0 && t <= 1.0) return a + t * r;
  }
  // Parallel (collinear overlap) or touching: an end of one lying on the other.
  for (const Eigen::Vector2d& p : {a, b})
    if (segmentsIntersect(p, p, c, d)) return p;
  for (const Eigen::Vector2d& p : {c, d})
    if (segmentsIntersect(p, p, a, b)) return p;
  return a;
}

double distanceToSegment(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((q - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

namespace {

// Even-odd rule: whether a ray from q crosses the polygon's edges an odd number of times. `at(i)`
// is vertex i of the n.
template <class Vertex>
bool insideEvenOdd(Eigen::Index n, Vertex at, const Eigen::Vector2d& q) {
  bool inside = false;
  for (Eigen::Index i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d a = at(i), b = at(j);
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < b.x() + (q.y() - b.y()) * (a.x() - b.x()) / (a.y() - b.y()))
      inside = !inside;
  }
  return inside;
}

}  // namespace

bool insidePolygon(const Points2& P, const Eigen::Vector2d& q) {
  return insideEvenOdd(
      P.rows(), [&](Eigen::Index i) -> Eigen::Vector2d { return P.row(i).transpose(); }, q);
}

bool insidePolygon(const std::vector<Eigen::Vector2d>& P, const Eigen::Vector2d& q) {
  return insideEvenOdd(
      Eigen::Index(P.size()), [&](Eigen::Index i) { return P[size_t(i)]; }, q);
}

}  // namespace dform
