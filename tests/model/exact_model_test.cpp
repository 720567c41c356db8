// The exact model's meshes follow the body's folds: every triangle lies in one face of the body
// and maps onto it isometrically, so the figures of an exact result are rounding, at every
// resolution, and no triangle of a piece straddles a fold.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "exact/body_edges.h"
#include "exact/shapes.h"
#include "model/exact_model.h"
#include "validate/metrics.h"

namespace dform {
namespace {

const std::string kPaths[2] = {"A", "B"};

// The exact D-Form of the seam polygons meshed with interior edges about a seam chord long.
Result<DForm> made(const exact::SeamPolygons& polygons, ModelUsed& used) {
  return exactDForm(polygons, closedLength(polygons.a) / double(polygons.a.rows()), kPaths, used);
}

// The figures that judge the object: with conforming meshes they are rounding.
void expectRounding(const Metrics& m, const std::string& what) {
  EXPECT_LE(m.L_max, 1e-8) << what;
  EXPECT_LE(m.L_error, 1e-9) << what;
  EXPECT_LE(m.gauss_max, 1e-8) << what;
  EXPECT_EQ(m.degenerate_2d + m.degenerate_3d, 0) << what;
  EXPECT_EQ(m.flipped_2d + m.flipped_3d, 0) << what;
}

TEST(ExactModel, EllipsePairMeshesConformAndTheFiguresAreRounding) {
  for (int n : {50, 100, 200}) {
    ModelUsed used;
    Result<DForm> model = made(exact::testshapes::ellipsePair(n), used);
    ASSERT_TRUE(model.isOk()) << n << ": " << model.status().message();
    expectRounding(computeMetrics(model.value()), "n = " + std::to_string(n));
  }
}

TEST(ExactModel, CircleAndSquareCreaseAndBendWithoutStretching) {
  const int perSide = 25;
  exact::SeamPolygons seam;
  const double radius = 200.0 / std::acos(-1.0);  // 400 mm round, as the square
  seam.a = exact::testshapes::ellipse(radius, radius, 4 * perSide);
  const Points2 square = exact::testshapes::polygonSampled({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, perSide);
  seam.b.resize(square.rows(), 2);
  for (Eigen::Index k = 0; k < square.rows(); ++k) seam.b.row(k) = square.row((square.rows() - k + perSide / 2) % square.rows());
  ModelUsed used;
  Result<DForm> model = made(seam, used);
  ASSERT_TRUE(model.isOk()) << model.status().message();
  // The square's flat face is triangulated by many flips, whose chained laws of cosines leave its
  // edges' lengths off by ~1e-7: the figures read that, not the meshing.
  const Metrics m = computeMetrics(model.value());
  EXPECT_LE(m.L_max, 5e-6);
  EXPECT_LE(m.gauss_max, 1e-6);
  EXPECT_EQ(m.degenerate_2d + m.degenerate_3d, 0);
  EXPECT_EQ(used.creases.size(), 4u) << "the disc creases between the square's corners";
}

// Whether a triangle's corners lie on both sides of the segment p-q (beyond rounding) while the
// segment passes through the triangle's inside: the triangle straddles that fold.
bool straddles(const Eigen::Vector2d t[3], const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = (q - p).normalized();
  double lo = 0, hi = 0, along[3];
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector2d r = t[c] - p;
    const double side = d.x() * r.y() - d.y() * r.x();
    lo = std::min(lo, side);
    hi = std::max(hi, side);
    along[c] = r.dot(d);
  }
  const double length = (q - p).norm(), slack = 1e-9 * length;
  const bool within = std::max({along[0], along[1], along[2]}) > slack && std::min({along[0], along[1], along[2]}) < length - slack;
  return lo < -slack && hi > slack && within;
}

TEST(ExactModel, NoTriangleStraddlesAFoldOfTheBody) {
  const exact::SeamPolygons polygons = exact::testshapes::ellipsePair(60);
  ModelUsed used;
  Result<DForm> model = made(polygons, used);
  ASSERT_TRUE(model.isOk()) << model.status().message();
  exact::SeamPolygons equal = polygons;
  exact::equalizeChords(equal);
  Result<exact::ExactGluing> glued = exact::glue(equal);
  ASSERT_TRUE(glued.isOk());
  Result<std::vector<exact::BodyEdge>> edges = exact::traceBodyEdges(glued.value());
  ASSERT_TRUE(edges.isOk()) << edges.status().message();
  int folds = 0;
  for (const exact::BodyEdge& edge : edges.value()) {
    if (edge.fold < 1e-3) continue;
    for (const exact::EdgeRun& run : edge.runs) {
      ++folds;
      const Piece& piece = run.piece == 0 ? model.value().a : model.value().b;
      const Eigen::Vector2d p = exact::seamPlacePoint(glued.value(), run.piece, run.from),
                            q = exact::seamPlacePoint(glued.value(), run.piece, run.to);
      for (Eigen::Index f = 0; f < piece.F.rows(); ++f) {
        const Eigen::Vector2d t[3] = {piece.flat.row(piece.F(f, 0)), piece.flat.row(piece.F(f, 1)),
                                      piece.flat.row(piece.F(f, 2))};
        ASSERT_FALSE(straddles(t, p, q)) << "triangle " << f << " of piece " << run.piece << " straddles the fold from seam point "
                                         << edge.from << " to " << edge.to;
      }
    }
  }
  EXPECT_GT(folds, 50) << "a curved body folds along many lines through its pieces";
}

}  // namespace
}  // namespace dform
