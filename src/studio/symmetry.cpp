// SPDX-License-Identifier: GPL-3.0-or-later
#include "symmetry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"

namespace dform::studio {

namespace {

constexpr int kMaxAxes = 12;
using Vec = Eigen::Vector2d;

double segmentDistance(const Vec& q, const Vec& a, const Vec& b) {
  const Vec d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - q).norm();
}

// The largest distance of Q's mirror image in the line through c at angle theta from the closed
// polyline Q.
double mirrorDeviation(const Eigen::MatrixXd& Q, const Vec& c, double theta) {
  const Vec u(std::cos(theta), std::sin(theta));
  const Eigen::Index m = Q.rows();
  double worst = 0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const Vec p = Q.row(i).transpose() - c;
    const Vec r = c + 2 * p.dot(u) * u - p;
    double nearest = INFINITY;
    for (Eigen::Index j = 0; j < m; ++j)
      nearest = std::min(nearest,
                         segmentDistance(r, Q.row(j).transpose(), Q.row((j + 1) % m).transpose()));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// The area centroid of the closed polygon P.
Vec centroid(const Points2& P) {
  Vec sum = Vec::Zero();
  double area2 = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Vec a = P.row(i).transpose(), b = P.row((i + 1) % P.rows()).transpose();
    const double cross = a.x() * b.y() - a.y() * b.x();
    sum += cross * (a + b);
    area2 += cross;
  }
  return area2 != 0 ? Vec(sum / (3 * area2)) : Vec(P.colwise().mean().transpose());
}

// Arc-length fractions of P where the line through c along u crosses it.
std::vector<double> crossings(const Points2& P, const Vec& c, const Vec& u) {
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = closedLength(P);
  const Vec normal(-u.y(), u.x());
  std::vector<double> out;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Vec a = P.row(i).transpose(), b = P.row((i + 1) % P.rows()).transpose();
    const double da = (a - c).dot(normal), db = (b - c).dot(normal);
    if ((da > 0 && db > 0) || (da < 0 && db < 0) || da == db) continue;
    const double t = da / (da - db);
    if (t >= 1) continue;  // the segment's end: the next segment's start
    out.push_back((s[i] + t * (b - a).norm()) / total);
  }
  return out;
}

}  // namespace

std::vector<double> symmetryFractions(const Points2& P) {
  if (P.rows() < 3 || closedLength(P) <= 0) return {};
  // Sought on 48 points every half degree (a few milliseconds: the studio answers every outline
  // with its axes), refined and judged on 120.
  const int steps = 360;
  const Eigen::MatrixXd coarse = resampleClosed(P, 48), Q = resampleClosed(P, 120);
  const Vec c = centroid(P);
  double radius = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    radius = std::max(radius, (P.row(i).transpose() - c).norm());
  const double tolerance = 1e-3 * 2 * radius;
  std::vector<double> deviation(steps);
  for (int k = 0; k < steps; ++k) deviation[k] = mirrorDeviation(coarse, c, kPi * k / steps);
  std::vector<double> out;
  int axes = 0;
  for (int k = 0; k < steps; ++k) {
    const double here = deviation[k];
    if (here > deviation[(k + steps - 1) % steps] || here > deviation[(k + 1) % steps]) continue;
    if (here == deviation[(k + steps - 1) % steps]) continue;  // a flat minimum counts once
    if (here > 20 * tolerance) continue;                       // no axis near
    // Golden-section search for the best angle within a step either side.
    double lo = kPi * (k - 1) / steps, hi = kPi * (k + 1) / steps;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 14; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (mirrorDeviation(Q, c, x1) < mirrorDeviation(Q, c, x2))
        hi = x2;
      else
        lo = x1;
    }
    const double theta = (lo + hi) / 2;
    if (mirrorDeviation(Q, c, theta) > tolerance) continue;
    const std::vector<double> cut = crossings(P, c, Vec(std::cos(theta), std::sin(theta)));
    out.insert(out.end(), cut.begin(), cut.end());
    if (++axes > kMaxAxes) return {};  // a circle's: every point is on one
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace dform::studio
