// The forward-mode samples: every pair reads as one outline each, with equal perimeters (a
// D-Form zips two pieces of equal perimeter), and the "nonconvex" ones really are non-convex.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "core/polyline.h"
#include "io/outline_reader.h"

namespace dform {
namespace {

const std::string kSamples = std::string(DFORM_SAMPLES_DIR) + "/forward/";

const std::pair<const char*, const char*> kPairs[] = {
    {"ellipses-a.svg", "ellipses-b.svg"},
    {"circle.svg", "square.svg"},
    {"nonconvex-a.svg", "nonconvex-b.svg"},
};

double perimeterOf(const std::string& name, double tolerance) {
  OutlineReadOptions options;
  options.flattenTolerance = tolerance;
  const Result<Shape2> shape = readShape(kSamples + name, options);
  EXPECT_TRUE(shape.isOk()) << shape.status().message();
  if (!shape.isOk()) return 0.0;
  EXPECT_TRUE(shape.value().holes.empty()) << name;
  EXPECT_GT(signedArea(shape.value().outer.points), 0.0) << name;
  return closedLength(shape.value().outer.points);
}

/// Area of the convex hull (monotone chain).
double hullArea(const Points2& P) {
  std::vector<Eigen::Vector2d> pts;
  for (Eigen::Index i = 0; i < P.rows(); ++i) pts.push_back(P.row(i).transpose());
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
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
    EXPECT_NEAR(pa / pb, 1.0, 1e-3) << a << " " << pa << " vs " << b << " " << pb;
    // Finely flattened, the designed sizes agree far better (chord deficit <= 2 pi x tolerance).
    const double fineA = perimeterOf(a, 1e-4), fineB = perimeterOf(b, 1e-4);
    EXPECT_NEAR(fineA / fineB, 1.0, 1e-5) << a << " " << fineA << " vs " << b << " " << fineB;
  }
}

TEST(Samples, EveryForwardSampleIsInAPair) {
  std::set<std::string> paired;
  for (const auto& [a, b] : kPairs) paired.insert({a, b});
  for (const auto& entry : std::filesystem::directory_iterator(kSamples))
    if (entry.path().extension() == ".svg") {
      EXPECT_TRUE(paired.count(entry.path().filename().string())) << entry.path();
    }
}

TEST(Samples, NonConvexSamplesAreNonConvex) {
  for (const char* name : {"nonconvex-a.svg", "nonconvex-b.svg"}) {
    const Result<Shape2> shape = readShape(kSamples + name);
    ASSERT_TRUE(shape.isOk()) << shape.status().message();
    const Points2& P = shape.value().outer.points;
    EXPECT_GT(hullArea(P), 1.002 * signedArea(P)) << name;
  }
}

}  // namespace
}  // namespace dform
