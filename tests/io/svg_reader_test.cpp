// SPDX-License-Identifier: GPL-3.0-or-later
// SVG outlines: units and viewports, transforms, curve flattening against exact lengths,
// orientation and the y-flip, holes, hidden and <defs> content.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "test_util.h"

namespace dform {
namespace {

constexpr double kPxPerMm = 96.0 / 25.4;

/// Full-precision decimal for writing test SVGs.
std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string svgDocument(const std::string& rootAttributes, const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" " + rootAttributes + ">\n" + body +
         "\n</svg>\n";
}

/// Reads a shape that must be valid.
Shape2 readOk(const std::string& path, const OutlineReadOptions& options = {}) {
  Result<Shape2> shape = readOutline(path, options);
  EXPECT_TRUE(shape.isOk()) << shape.status().message();
  return shape.isOk() ? shape.value() : Shape2{};
}

double perimeter(const Shape2& shape) { return closedLength(shape.outer.points); }

/// A flattened convex curve loses at most (tolerance / 3) x (total turning) of its length to the
/// chords (chord deficit ~ 8 d^2 / (3 c) per chord of length c and deviation d <= tolerance, and
/// d ~ curvature c^2 / 8). 2 pi x tolerance bounds that for every closed convex outline here.
void expectFlattenedLength(double length, double exact, double tolerance) {
  EXPECT_LE(length, exact + 1e-9 * exact);
  EXPECT_GE(length, exact - 2 * M_PI * tolerance);
}

TEST(SvgUnits, MillimetrePageWithPixelViewBox) {
  test::ScratchDir dir;
  const std::string body = "<rect x='" + num(20 * kPxPerMm) + "' y='" + num(30 * kPxPerMm) +
                           "' width='" + num(100 * kPxPerMm) + "' height='" + num(50 * kPxPerMm) +
                           "'/>";
  const std::string path =
      dir.write("a4.svg", svgDocument("width='210mm' height='297mm' viewBox='0 0 " +
                                          num(210 * kPxPerMm) + " " + num(297 * kPxPerMm) + "'",
                                      body));
  const Shape2 shape = readOk(path);
  EXPECT_NEAR(perimeter(shape), 300.0, 1e-6);
  EXPECT_NEAR(signedArea(shape.outer.points), 5000.0, 1e-6);
  EXPECT_EQ(shape.outer.source, path);
  EXPECT_TRUE(shape.holes.empty());
}

TEST(SvgUnits, MillimetrePageWithUserUnitViewBox) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("mm.svg", svgDocument("width='210mm' height='297mm' viewBox='0 0 210 297'",
                                      "<rect x='20' y='30' width='100' height='50'/>"));
  EXPECT_NEAR(perimeter(readOk(path)), 300.0, 1e-6);
}

TEST(SvgUnits, InchPage) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("letter.svg", svgDocument("width='8.5in' height='11in' viewBox='0 0 8.5 11'",
                                          "<rect x='1' y='1' width='" + num(100 / 25.4) +
                                              "' height='" + num(50 / 25.4) + "'/>"));
  EXPECT_NEAR(perimeter(readOk(path)), 300.0, 1e-6);
}

TEST(SvgUnits, NoSizeMeansPixels) {
  test::ScratchDir dir;
  const std::string rect =
      "<rect width='" + num(100 * kPxPerMm) + "' height='" + num(50 * kPxPerMm) + "'/>";
  EXPECT_NEAR(perimeter(readOk(dir.write("plain.svg", svgDocument("", rect)))), 300.0, 1e-6);
  // A viewBox alone keeps user unit = px.
  EXPECT_NEAR(perimeter(readOk(dir.write("box.svg", svgDocument("viewBox='0 0 1000 1000'", rect)))),
              300.0, 1e-6);
}

TEST(SvgUnits, UnitsOnElementLengths) {
  test::ScratchDir dir;
  EXPECT_NEAR(
      perimeter(readOk(dir.write("cm.svg", svgDocument("", "<rect width='100mm' height='5cm'/>")))),
      300.0, 1e-6);
  EXPECT_NEAR(perimeter(readOk(dir.write(
                  "pt.svg", svgDocument("", "<rect width='" + num(100 / 25.4 * 72) +
                                                "pt' height='" + num(50 / 25.4 * 6) + "pc'/>")))),
              300.0, 1e-6);
}

TEST(SvgUnits, PageSizeInPointsAndPicas) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("pt-page.svg", svgDocument("width='" + num(200 / 25.4 * 72) + "pt' height='" +
                                               num(100 / 25.4 * 6) + "pc' viewBox='0 0 200 100'",
                                           "<rect width='100' height='50'/>"));
  EXPECT_NEAR(perimeter(readOk(path)), 300.0, 1e-6);
}

TEST(SvgUnits, PreserveAspectRatio) {
  test::ScratchDir dir;
  // "none" stretches 100 x 100 user units onto 200 mm x 100 mm.
  EXPECT_NEAR(perimeter(readOk(dir.write(
                  "none.svg", svgDocument("width='200mm' height='100mm' viewBox='0 0 100 100' "
                                          "preserveAspectRatio='none'",
                                          "<rect width='50' height='50'/>")))),
              300.0, 1e-6);
  // The default (xMidYMid meet) scales uniformly by the smaller ratio: 1 mm per unit.
  const Shape2 meet =
      readOk(dir.write("meet.svg", svgDocument("width='200mm' height='100mm' viewBox='0 0 100 100'",
                                               "<rect width='100' height='50'/>")));
  EXPECT_NEAR(perimeter(meet), 300.0, 1e-6);
  EXPECT_NEAR(meet.outer.points.col(0).minCoeff(), 50.0, 1e-9);  // centred horizontally
}

TEST(SvgTransforms, NestedGroupsWithScaleRotateTranslate) {
  test::ScratchDir dir;
  const std::string body =
      "<g transform='translate(40,150) scale(2)'>"
      "  <g transform='rotate(30)'>"
      "    <rect width='25' height='12.5' transform='scale(2 2)'/>"
      "  </g>"
      "</g>";
  const Shape2 shape = readOk(dir.write(
      "nested.svg", svgDocument("width='210mm' height='297mm' viewBox='0 0 210 297'", body)));
  EXPECT_NEAR(perimeter(shape), 300.0, 1e-9);
  EXPECT_NEAR(signedArea(shape.outer.points), 5000.0, 1e-9);
  // The rect's corner (0, 0) lands on the group origin (40, 150), i.e. y = 297 - 150 upwards; its
  // long side is rotated 30 degrees clockwise on screen, so it descends in the y-up frame.
  bool foundOrigin = false, foundLongCorner = false;
  for (Eigen::Index i = 0; i < shape.outer.points.rows(); ++i) {
    const Eigen::Vector2d p = shape.outer.points.row(i);
    foundOrigin |= (p - Eigen::Vector2d(40, 147)).norm() < 1e-9;
    foundLongCorner |=
        (p - Eigen::Vector2d(40 + 100 * std::cos(M_PI / 6), 147 - 100 * std::sin(M_PI / 6)))
            .norm() < 1e-9;
  }
  EXPECT_TRUE(foundOrigin);
  EXPECT_TRUE(foundLongCorner);
}

TEST(SvgTransforms, MatrixSkewAndElementTransformOnPath) {
  test::ScratchDir dir;
  // skewX keeps area; matrix(2 0 0 0.5 0 0) keeps area too.
  const std::string body =
      "<g transform='matrix(2 0 0 0.5 0 0)'><path transform='skewX(20)' d='M0 0 h50 v80 h-50 "
      "z'/></g>";
  const Shape2 shape = readOk(dir.write(
      "skew.svg", svgDocument("viewBox='0 0 500 500' width='500mm' height='500mm'", body)));
  EXPECT_NEAR(signedArea(shape.outer.points), 4000.0, 1e-9);
}

TEST(SvgCurves, CircleLengthWithinFlattenTolerance) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("circle.svg", svgDocument("width='100mm' height='100mm' viewBox='0 0 100 100'",
                                          "<circle cx='50' cy='50' r='20'/>"));
  for (double tolerance : {0.5, 0.01, 0.001}) {
    OutlineReadOptions options;
    options.flattenTolerance = tolerance;
    const Shape2 shape = readOk(path, options);
    const Points2& P = shape.outer.points;
    expectFlattenedLength(closedLength(P), 2 * M_PI * 20, tolerance);
    // Every vertex is on the circle and every chord midpoint within the tolerance of it.
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d c(50, 50);
      EXPECT_NEAR((Eigen::Vector2d(P.row(i)) - c).norm(), 20.0, 1e-9);
      const Eigen::Vector2d mid = 0.5 * (P.row(i) + P.row((i + 1) % P.rows())).transpose();
      EXPECT_LE(20.0 - (mid - c).norm(), tolerance);
    }
  }
}

TEST(SvgCurves, CircleInMillimetresOnPixelPage) {
  test::ScratchDir dir;
  const Shape2 shape =
      readOk(dir.write("circle-mm.svg", svgDocument("", "<circle cx='30mm' cy='30mm' r='20mm'/>")));
  expectFlattenedLength(perimeter(shape), 2 * M_PI * 20, 0.01);
}

/// Perimeter of an ellipse by Gauss-Kummer series (converges fast for moderate eccentricity).
double ellipsePerimeter(double a, double b) {
  const double h = std::pow((a - b) / (a + b), 2);
  double term = 1.0, sum = 1.0;
  for (int n = 1; n < 60; ++n) {
    // binomial(1/2, n)^2 h^n
    term *= (0.5 - (n - 1)) / n;
    sum += term * term * std::pow(h, n);
  }
  return M_PI * (a + b) * sum;
}

TEST(SvgCurves, EllipseAndRotatedArcs) {
  test::ScratchDir dir;
  const std::string page = "width='300mm' height='300mm' viewBox='0 0 300 300'";
  expectFlattenedLength(
      perimeter(readOk(
          dir.write("e.svg", svgDocument(page, "<ellipse cx='150' cy='150' rx='60' ry='30'/>")))),
      ellipsePerimeter(60, 30), 0.01);
  // The same ellipse drawn as two arcs with the axes rotated by 30 degrees.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const std::string d = "M" + num(150 + 60 * c) + "," + num(150 + 60 * s) + " A60 30 30 1 1 " +
                        num(150 - 60 * c) + "," + num(150 - 60 * s) + " A60 30 30 1 1 " +
                        num(150 + 60 * c) + "," + num(150 + 60 * s) + "Z";
  const Shape2 rotated = readOk(dir.write("arcs.svg", svgDocument(page, "<path d='" + d + "'/>")));
  expectFlattenedLength(perimeter(rotated), ellipsePerimeter(60, 30), 0.01);
  EXPECT_NEAR(signedArea(rotated.outer.points), M_PI * 60 * 30, 2 * M_PI * 60 * 0.01);
}

TEST(SvgCurves, HalfDiscArcWithRelativeCommands) {
  test::ScratchDir dir;
  const Shape2 shape =
      readOk(dir.write("half.svg", svgDocument("width='200mm' height='200mm' viewBox='0 0 200 200'",
                                               "<path d='m 50 100 a 50 50 0 0 1 100 0 z'/>")));
  expectFlattenedLength(perimeter(shape), 100 + M_PI * 50, 0.01);
  // Sweep flag 1 on screen (y down) is clockwise: the bulge is above the chord on screen, i.e.
  // at larger y in the y-up frame (page height 200, chord at 100); the top is sampled or lies
  // within the flatten tolerance of a chord.
  const double top = shape.outer.points.col(1).maxCoeff();
  EXPECT_LE(top, 150.0 + 1e-9);
  EXPECT_GE(top, 150.0 - OutlineReadOptions{}.flattenTolerance);
}

TEST(SvgCurves, TooSmallRadiiAreScaledUp) {
  test::ScratchDir dir;
  // rx = ry = 1 cannot span 100 units: SVG scales the radii up to a half circle.
  const Shape2 shape = readOk(
      dir.write("small-r.svg", svgDocument("width='200mm' height='200mm' viewBox='0 0 200 200'",
                                           "<path d='M50 100 A1 1 0 0 0 150 100Z'/>")));
  expectFlattenedLength(perimeter(shape), 100 + M_PI * 50, 0.01);
}

/// Length of the parabolic arc Q(0,0)-(50,100)-(100,0): y = 2x - x^2/50 over [0, 100],
/// integral of sqrt(1 + y'^2) = 25 * (2 sqrt 5 + asinh 2).
const double kParabolaLength = 25 * (2 * std::sqrt(5.0) + std::asinh(2.0));

TEST(SvgCurves, QuadraticBezierAgainstExactLength) {
  test::ScratchDir dir;
  const std::string page = "width='300mm' height='300mm' viewBox='0 0 300 300'";
  expectFlattenedLength(perimeter(readOk(dir.write(
                            "q.svg", svgDocument(page, "<path d='M0 200 Q50 100 100 200 Z'/>")))),
                        kParabolaLength + 100, 0.01);
  // Relative q, smooth t (mirrored control point), h and v.
  const Shape2 shape = readOk(dir.write(
      "t.svg", svgDocument(page, "<path d='m0 200 q50 -100 100 0 t100 0 v150 h-200 z'/>")));
  expectFlattenedLength(perimeter(shape), 2 * kParabolaLength + 500, 0.01);
}

TEST(SvgCurves, CubicBezierAgainstExactLength) {
  test::ScratchDir dir;
  const std::string page = "width='300mm' height='300mm' viewBox='0 0 300 300'";
  // The cubic with control points at 2/3 of the quadratic's is the same parabola.
  const double a = 100.0 / 3, b = 200.0 / 3;
  const std::string d = "M0 200 C" + num(a) + " " + num(200 - b) + " " + num(b) + " " +
                        num(200 - b) + " 100 200 S" + num(200 - a) + " " + num(200 + b) +
                        " 200 200 V350 H0 Z";
  expectFlattenedLength(
      perimeter(readOk(dir.write("c.svg", svgDocument(page, "<path d='" + d + "'/>")))),
      2 * kParabolaLength + 500, 0.01);
  // The same curve in relative coordinates with a relative smooth cubic.
  const std::string rel = "m0 200 c" + num(a) + " " + num(-b) + " " + num(b) + " " + num(-b) +
                          " 100 0 s" + num(100 - a) + " " + num(b) + " 100 0 v150 h-200 z";
  expectFlattenedLength(
      perimeter(readOk(dir.write("cr.svg", svgDocument(page, "<path d='" + rel + "'/>")))),
      2 * kParabolaLength + 500, 0.01);
}

TEST(SvgCurves, RoundedRect) {
  test::ScratchDir dir;
  const Shape2 shape = readOk(dir.write(
      "rounded.svg", svgDocument("width='200mm' height='200mm' viewBox='0 0 200 200'",
                                 "<rect x='10' y='10' width='100' height='60' rx='10' ry='10'/>")));
  expectFlattenedLength(perimeter(shape), 2 * (100 + 60) - 8 * 10 + 2 * M_PI * 10, 0.01);
}

TEST(SvgOrientation, OutputIsCounterClockwiseWhicheverWayItWasDrawn) {
  test::ScratchDir dir;
  const std::string page = "width='100mm' height='100mm' viewBox='0 0 100 100'";
  for (const char* d : {"M10 10 H90 V90 H10 Z", "M10 10 V90 H90 V10 Z"}) {
    const Shape2 shape =
        readOk(dir.write("o.svg", svgDocument(page, std::string("<path d='") + d + "'/>")));
    EXPECT_NEAR(signedArea(shape.outer.points), 6400.0, 1e-9) << d;
  }
}

TEST(SvgOrientation, YFlipDoesNotMirror) {
  test::ScratchDir dir;
  // An L on screen: tall bar on the left, foot at the bottom pointing right. In the y-up page
  // frame every point (x, y) must appear as (x, 120 - y): same picture, not its mirror image.
  const double pts[][2] = {{10, 10}, {30, 10}, {30, 90}, {80, 90}, {80, 110}, {10, 110}};
  std::string list;
  for (const auto& p : pts) list += num(p[0]) + "," + num(p[1]) + " ";
  const Shape2 shape =
      readOk(dir.write("L.svg", svgDocument("width='100mm' height='120mm' viewBox='0 0 100 120'",
                                            "<polygon points='" + list + "'/>")));
  const Points2& P = shape.outer.points;
  ASSERT_EQ(P.rows(), 6);
  for (const auto& p : pts) {
    bool found = false;
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      found |= (P.row(i) - Eigen::RowVector2d(p[0], 120 - p[1])).norm() < 1e-12;
    EXPECT_TRUE(found) << p[0] << "," << p[1];
  }
  // The foot (x up to 80) is at the bottom of the y-up frame.
  Eigen::Index right = 0;
  P.col(0).maxCoeff(&right);
  EXPECT_LT(P(right, 1), 30.0);
  EXPECT_GT(signedArea(P), 0.0);
}

TEST(SvgAssembly, ShapeInsideIsAHole) {
  test::ScratchDir dir;
  const Shape2 shape = readOk(dir.write(
      "holes.svg",
      svgDocument("width='200mm' height='200mm' viewBox='0 0 200 200'",
                  "<circle cx='60' cy='100' r='20'/><rect x='10' y='10' width='180' height='180'/>"
                  "<path d='M120 80 h40 v40 h-40 z'/>")));
  EXPECT_NEAR(perimeter(shape), 720.0, 1e-9);
  ASSERT_EQ(shape.holes.size(), 2u);
  for (const Outline2& hole : shape.holes) EXPECT_GT(signedArea(hole.points), 0.0);
}

TEST(SvgAssembly, PathWithTwoSubpathsIsARing) {
  test::ScratchDir dir;
  const Shape2 shape = readOk(dir.write(
      "ring.svg",
      svgDocument(
          "width='200mm' height='200mm' viewBox='0 0 200 200'",
          "<path fill-rule='evenodd' d='M10 10 H190 V190 H10 Z M50 50 V150 H150 V50 Z'/>")));
  ASSERT_EQ(shape.holes.size(), 1u);
  EXPECT_NEAR(signedArea(shape.holes[0].points), 10000.0, 1e-9);
}

TEST(SvgAssembly, DefsHiddenAndNonSvgContentIgnored) {
  test::ScratchDir dir;
  const std::string body =
      "<defs><rect id='template' x='300' width='100' height='100'/></defs>"
      "<metadata><foo xmlns='urn:x'><rect width='1' height='1'/></foo></metadata>"
      "<rect x='300' y='300' width='10' height='10' display='none'/>"
      "<g style='fill:red; display : none'><circle cx='400' cy='400' r='5'/></g>"
      "<text x='0' y='0'>label</text>"
      "<g><rect x='10' y='10' width='100' height='50' style='stroke:black;-inkscape-foo:1'/></g>";
  const Shape2 shape = readOk(dir.write(
      "hidden.svg", svgDocument("width='500mm' height='500mm' viewBox='0 0 500 500'", body)));
  EXPECT_NEAR(perimeter(shape), 300.0, 1e-9);
  EXPECT_TRUE(shape.holes.empty());
}

TEST(SvgAssembly, MissingNamespaceAndClosedPolylineAccepted) {
  test::ScratchDir dir;
  const Shape2 shape =
      readOk(dir.write("bare.svg",
                       "<?xml version='1.0'?>\n<!-- hand written -->\n<svg width='100mm' "
                       "height='100mm' viewBox='0 0 100 100'>"
                       "<polyline points='10,10 60,10 60,60 10,60 10,10'/></svg>"));
  EXPECT_NEAR(perimeter(shape), 200.0, 1e-9);
  EXPECT_EQ(shape.outer.points.rows(), 4);  // the closing point is not repeated
}

TEST(SvgAssembly, NoConsecutiveDuplicates) {
  test::ScratchDir dir;
  const Shape2 shape = readOk(dir.write(
      "dups.svg",
      svgDocument("width='100mm' height='100mm' viewBox='0 0 100 100'",
                  "<path d='M10 10 L10 10 L60 10 L60 10 L60 60 Q60 60 60 60 L10 60 L10 10 Z'/>")));
  const Points2& P = shape.outer.points;
  EXPECT_EQ(P.rows(), 4);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    EXPECT_GT((P.row(i) - P.row((i + 1) % P.rows())).norm(), 0.0);
}

TEST(SvgFiles, DataFilesRead) {
  // Files as an editor writes them (XML declaration, namespaces, metadata, groups).
  const Shape2 kidney = readOk(std::string(DFORM_TEST_DATA_DIR) + "/inkscape-style.svg");
  EXPECT_GT(signedArea(kidney.outer.points), 0.0);
  EXPECT_NEAR(perimeter(kidney), 300.0, 1e-6);
}

}  // namespace
}  // namespace dform
