// SPDX-License-Identifier: GPL-3.0-or-later
// The forward-mode samples: every pair reads as one piece each whose joined boundaries (outlines,
// or holes for the anti and demi D-Forms) have equal lengths (a D-Form zips two boundaries of
// equal length), the "nonconvex" ones really are non-convex, and the Squaricle disc has its four
// creases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"

namespace dform {
namespace {

const std::string kSamples = std::string(DFORM_SAMPLES_DIR) + "/forward/";

// Each piece with the boundary its job zips: its outline, or its one hole.
struct Joined {
  const char* file;
  bool hole;
};
const std::pair<Joined, Joined> kPairs[] = {
    {{"ellipses-a.svg", false}, {"ellipses-b.svg", false}},
    {{"circle.svg", false}, {"square.svg", false}},
    {{"nonconvex-a.svg", false}, {"nonconvex-b.svg", false}},
    {{"anti-a.svg", true}, {"anti-b.svg", true}},
    {{"demi-disc.svg", false}, {"demi-ring.svg", true}},
    {{"squaricle-disc.svg", false}, {"squaricle-square.svg", false}},
};

double perimeterOf(const Joined& piece, double tolerance) {
  OutlineReadOptions options;
  options.flattenTolerance = tolerance;
  const Result<Shape2> shape = readOutline(kSamples + piece.file, options);
  EXPECT_TRUE(shape.isOk()) << shape.status().message();
  if (!shape.isOk()) return 0.0;
  EXPECT_EQ(shape.value().holes.size(), piece.hole ? 1u : 0u) << piece.file;
  const Points2& joined = piece.hole ? shape.value().holes[0].points : shape.value().outer.points;
  EXPECT_GT(signedArea(joined), 0.0) << piece.file;
  return closedLength(joined);
}

/// Area of the convex hull (monotone chain).
double hullArea(const Points2& P) {
  std::vector<Eigen::Vector2d> pts;
  for (Eigen::Index i = 0; i < P.rows(); ++i) pts.push_back(P.row(i).transpose());
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  Points2 H(Eigen::Index(k - 1), 2);
  for (std::size_t i = 0; i + 1 < k; ++i) H.row(Eigen::Index(i)) = hull[i].transpose();
  return signedArea(H);
}

TEST(Samples, PairsHaveEqualPerimeters) {
  for (const auto& [a, b] : kPairs) {
    // At the default tolerance, as the pipeline reads them.
    const double pa = perimeterOf(a, OutlineReadOptions{}.flattenTolerance);
    const double pb = perimeterOf(b, OutlineReadOptions{}.flattenTolerance);
    EXPECT_NEAR(pa / pb, 1.0, 1e-3) << a.file << " " << pa << " vs " << b.file << " " << pb;
    // Finely flattened, the designed sizes agree far better (chord deficit <= 2 pi x tolerance).
    const double fineA = perimeterOf(a, 1e-4), fineB = perimeterOf(b, 1e-4);
    EXPECT_NEAR(fineA / fineB, 1.0, 1e-5)
        << a.file << " " << fineA << " vs " << b.file << " " << fineB;
  }
}

TEST(Samples, EveryForwardSampleIsInAPair) {
  std::set<std::string> paired;
  for (const auto& [a, b] : kPairs) paired.insert({a.file, b.file});
  for (const auto& entry : std::filesystem::directory_iterator(kSamples))
    if (entry.path().extension() == ".svg") {
      EXPECT_TRUE(paired.count(entry.path().filename().string())) << entry.path();
    }
}

TEST(Samples, NonConvexSamplesAreNonConvex) {
  for (const char* name : {"nonconvex-a.svg", "nonconvex-b.svg"}) {
    const Result<Shape2> shape = readOutline(kSamples + name);
    ASSERT_TRUE(shape.isOk()) << shape.status().message();
    const Points2& P = shape.value().outer.points;
    EXPECT_GT(hullArea(P), 1.002 * signedArea(P)) << name;
  }
}

TEST(Samples, SquaricleDiscHasFourCreasesJoiningItsQuarterPoints) {
  const Result<Shape2> shape = readOutline(kSamples + "squaricle-disc.svg");
  ASSERT_TRUE(shape.isOk()) << shape.status().message();
  ASSERT_EQ(shape.value().creases.size(), 4u);
  const double radius = 200.0 / M_PI;
  for (const CreaseLine& crease : shape.value().creases) {
    // A quarter chord, its ends on the circle as flattened (within the flatten tolerance of it
    // across the circle, so within sqrt(2) times that along the chord, which meets it at 45°).
    const double tolerance = OutlineReadOptions{}.flattenTolerance;
    EXPECT_NEAR(openLength(crease.points), radius * std::sqrt(2.0), 2 * std::sqrt(2.0) * tolerance)
        << crease.label;
    for (const Eigen::Index end : {Eigen::Index(0), crease.points.rows() - 1})
      EXPECT_NEAR((crease.points.row(end) - Eigen::RowVector2d(80, 80)).norm(), radius, tolerance)
          << crease.label;
  }
}

}  // namespace
}  // namespace dform
