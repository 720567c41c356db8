#include "core/polyline.h"

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

std::optional<std::pair<int, int>> findSelfIntersection(const Points2& P) {
  const int n = int(P.rows());
  if (n < 4) return std::nullopt;
  // Sweep over x: sort edges by their left end and compare only edges whose x-ranges overlap.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto minX = [&](int e) { return std::min(P(e, 0), P((e + 1) % n, 0)); };
  auto maxX = [&](int e) { return std::max(P(e, 0), P((e + 1) % n, 0)); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return minX(a) < minX(b); });
  for (int oi = 0; oi < n; ++oi) {
    const int e = order[oi];
    const double reach = maxX(e);
    for (int oj = oi + 1; oj < n && minX(order[oj]) <= reach; ++oj) {
      const int f = order[oj];
      const int gap = std::abs(e - f);
      if (gap == 1 || gap == n - 1) continue;  // neighbours share a vertex by construction
      if (segmentsIntersect(P.row(e), P.row((e + 1) % n), P.row(f), P.row((f + 1) % n)))
        return std::make_pair(std::min(e, f), std::max(e, f));
    }
  }
  return std::nullopt;
}

}  // namespace dform
