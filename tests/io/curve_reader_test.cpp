// SPDX-License-Identifier: GPL-3.0-or-later
// Seam curves: OBJ polylines (index forms, closing), JSON points and closed cubic Beziers, and
// every bad input.
#include "dform/io/curve_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dform/core/polyline.h"
#include "test_util.h"

namespace dform {
namespace {

using test::failsWith;

/// OBJ vertex lines for n samples c(t), t = 2 pi (i + phase) / n.
template <typename Curve>
std::string vertices(int n, Curve c, double phase = 0.0) {
  std::string text;
  char line[128];
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = c(2 * M_PI * (i + phase) / n);
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    text += line;
  }
  return text;
}

/// A saddle-shaped closed curve: x, y on a circle of radius 50, z = 10 cos 2t.
std::string saddleVertices(int n) {
  return vertices(n, [](double t) {
    return Eigen::Vector3d(50 * std::cos(t), 50 * std::sin(t), 10 * std::cos(2 * t));
  });
}

std::string indexList(int n, bool repeatFirst) {
  std::string text = "l";
  for (int i = 1; i <= n; ++i) text += " " + std::to_string(i);
  return text + (repeatFirst ? " 1\n" : "\n");
}

TEST(CurveObj, ClosedByRepeatedIndex) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("seam.obj", "# seam\no seam\n" + saddleVertices(64) + indexList(64, true));
  const Result<Curve3> curve = readCurve(path);
  ASSERT_TRUE(curve.isOk()) << curve.status().message();
  EXPECT_EQ(curve.value().points.rows(), 64);  // the closing index is not repeated
  EXPECT_EQ(curve.value().source, path);
  EXPECT_NEAR(curve.value().points(10, 2), 10 * std::cos(2 * 2 * M_PI * 10 / 64), 1e-12);
}

TEST(CurveObj, NegativeAndSlashIndices) {
  test::ScratchDir dir;
  // Relative indices count back from the latest vertex; "i/t" forms use the vertex index.
  const std::string path =
      dir.write("rel.obj", saddleVertices(6) + "l -6/1 -5 -4 -3//2 -2 -1 -6\n");
  const Result<Curve3> curve = readCurve(path);
  ASSERT_TRUE(curve.isOk()) << curve.status().message();
  EXPECT_EQ(curve.value().points.rows(), 6);
  EXPECT_DOUBLE_EQ(curve.value().points(0, 0), 50.0);
}

TEST(CurveObj, OpenUnlessForcedClosed) {
  test::ScratchDir dir;
  const std::string path = dir.write("open.obj", saddleVertices(8) + indexList(8, false));
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path, "open"));
  CurveReadOptions options;
  options.forceClosed = true;
  const Result<Curve3> curve = readCurve(path, options);
  ASSERT_TRUE(curve.isOk()) << curve.status().message();
  EXPECT_EQ(curve.value().points.rows(), 8);
}

TEST(CurveObj, FacesButNoPolyline) {
  test::ScratchDir dir;
  const std::string path = dir.write("mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(
      failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path, "faces but no polyline"));
}

TEST(CurveObj, SeveralPolylines) {
  test::ScratchDir dir;
  const std::string path = dir.write("two.obj", saddleVertices(8) + "l 1 2 3 4 1\nl 5 6 7 8 5\n");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path, "2 polylines"));
}

TEST(CurveObj, MalformedLineNamesLineNumber) {
  test::ScratchDir dir;
  const std::string path = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 1 one 0\n");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputUnreadable, path, "line 3"));
  const std::string shortVertex = dir.write("short.obj", "v 0 0\n");
  EXPECT_TRUE(failsWith(readCurve(shortVertex).status(), ErrorCode::InputUnreadable, shortVertex,
                        "line 1"));
}

TEST(CurveObj, IndexOutOfRangeOrZero) {
  test::ScratchDir dir;
  const std::string high = dir.write("high.obj", saddleVertices(5) + "l 1 2 3 4 9 1\n");
  EXPECT_TRUE(
      failsWith(readCurve(high).status(), ErrorCode::InputUnreadable, high, "out of range"));
  const std::string zero = dir.write("zero.obj", saddleVertices(5) + "l 0 1 2 3 4 0\n");
  EXPECT_TRUE(failsWith(readCurve(zero).status(), ErrorCode::InputUnreadable, zero, "line 6"));
  const std::string back = dir.write("back.obj", saddleVertices(5) + "l -7 1 2\n");
  EXPECT_TRUE(failsWith(readCurve(back).status(), ErrorCode::InputUnreadable, back, "line 6"));
}

TEST(CurveObj, NotANumberCoordinate) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("nan.obj", saddleVertices(6) + "v nan 0 0\nl 1 2 3 7 4 5 6 1\n");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path,
                        "polyline point 4 (vertex 7) has a coordinate that is not a number"));
  const std::string inf =
      dir.write("inf.obj", saddleVertices(6) + "v 0 inf 0\nl 1 2 3 7 4 5 6 1\n");
  EXPECT_TRUE(failsWith(readCurve(inf).status(), ErrorCode::InputInvalid, inf, "infinite"));
}

TEST(CurveObj, HugeCoordinate) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("huge.obj", saddleVertices(6) + "v 0 0 5e6\nl 1 2 3 7 4 5 6 1\n");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path, "too large"));
}

TEST(CurveObj, RepeatedConsecutivePointsAreNamed) {
  test::ScratchDir dir;
  const std::string path = dir.write("dup.obj", saddleVertices(8) + "l 1 2 3 3 4 5 6 7 8 1\n");
  EXPECT_TRUE(
      failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path,
                "polyline point 3 (vertex 3) and polyline point 4 (vertex 3) are the same point"));
}

TEST(CurveObj, FewerThanFiveDistinctPoints) {
  test::ScratchDir dir;
  const std::string path = dir.write("four.obj", saddleVertices(4) + indexList(4, true));
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path,
                        "fewer than 5 distinct points"));
}

TEST(CurveObj, SelfIntersectingFigureEight) {
  test::ScratchDir dir;
  // A lemniscate crosses itself at the origin.
  const int n = 101;
  const std::string text = vertices(
      n, [](double t) { return Eigen::Vector3d(40 * std::cos(t), 20 * std::sin(2 * t), 3); }, 0.5);
  const std::string path = dir.write("eight.obj", text + indexList(n, true));
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path,
                        "crosses or touches itself near ("));
}

TEST(CurveObj, SkewCurvesThatComeCloseButDoNotTouchAreFine) {
  test::ScratchDir dir;
  // The same figure eight bent out of plane so the branches pass 2 mm apart at the crossing.
  const int n = 101;
  const std::string text = vertices(
      n,
      [](double t) { return Eigen::Vector3d(40 * std::cos(t), 20 * std::sin(2 * t), std::sin(t)); },
      0.5);
  const std::string path = dir.write("knot.obj", text + indexList(n, true));
  const Result<Curve3> curve = readCurve(path);
  EXPECT_TRUE(curve.isOk()) << curve.status().message();
}

TEST(CurveObj, PlanarCurveInAxisPlaneIsChecked) {
  test::ScratchDir dir;
  // All x equal: the sweep must still prune (and find no crossing) on a large circle.
  const int n = 20000;
  const std::string text = vertices(
      n, [](double t) { return Eigen::Vector3d(0, 100 * std::cos(t), 100 * std::sin(t)); });
  const std::string path = dir.write("yz.obj", text + indexList(n, true));
  const Result<Curve3> curve = readCurve(path);
  ASSERT_TRUE(curve.isOk()) << curve.status().message();
  EXPECT_NEAR(closedLength(curve.value().points), 2 * M_PI * 100, 1e-3);
}

TEST(CurveFiles, UnknownExtension) {
  test::ScratchDir dir;
  const std::string path = dir.write("seam.stl", "solid x\n");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputUnreadable, path, "'.stl'"));
}

TEST(CurveFiles, MissingFile) {
  test::ScratchDir dir;
  const std::string path = dir.path() + "/none.obj";
  EXPECT_TRUE(
      failsWith(readCurve(path).status(), ErrorCode::InputUnreadable, path, "no such file"));
}

TEST(CurveJson, PointsClosedByRepeat) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "seam.json", R"({"points": [[0,0,0],[10,0,1],[10,10,0],[0,10,1],[-5,5,2],[0,0,0]]})");
  const Result<Curve3> curve = readCurve(path);
  ASSERT_TRUE(curve.isOk()) << curve.status().message();
  EXPECT_EQ(curve.value().points.rows(), 5);
  const std::string open =
      dir.write("open.json", R"({"points": [[0,0,0],[10,0,1],[10,10,0],[0,10,1],[-5,5,2]]})");
  EXPECT_TRUE(failsWith(readCurve(open).status(), ErrorCode::InputInvalid, open, "open"));
  const std::string flat =
      dir.write("flat.json", R"({"points": [[0,0],[10,0],[10,10],[0,10],[-5,5],[0,0]]})");
  EXPECT_TRUE(failsWith(readCurve(flat).status(), ErrorCode::InputUnreadable, flat, "point 1"));
}

/// A circle of radius r as 4 cubic Beziers (control distance kappa r), tilted out of the plane.
std::string bezierCircle(double r) {
  const double k = 4.0 / 3.0 * (std::sqrt(2.0) - 1.0) * r;
  const double pts[12][2] = {{r, 0},  {r, k},   {k, r},   {0, r},  {-k, r}, {-r, k},
                             {-r, 0}, {-r, -k}, {-k, -r}, {0, -r}, {k, -r}, {r, -k}};
  std::string text = R"({"units": "mm", "bezier": [)";
  char item[96];
  for (int i = 0; i < 12; ++i) {
    // Rotate about the x axis by 30 degrees: lengths are unchanged.
    std::snprintf(item, sizeof item, "%s[%.17g, %.17g, %.17g]", i ? ", " : "", pts[i][0],
                  pts[i][1] * std::cos(M_PI / 6), pts[i][1] * std::sin(M_PI / 6));
    text += item;
  }
  return text + "]}";
}

TEST(CurveJson, BezierCircleLength) {
  test::ScratchDir dir;
  const std::string path = dir.write("circle.json", bezierCircle(80));
  for (double tolerance : {0.1, 0.01}) {
    CurveReadOptions options;
    options.flattenTolerance = tolerance;
    const Result<Curve3> curve = readCurve(path, options);
    ASSERT_TRUE(curve.isOk()) << curve.status().message();
    EXPECT_NEAR(closedLength(curve.value().points), 2 * M_PI * 80, 1e-3 * 2 * M_PI * 80);
    // Flattening keeps every point near the circle (the 4-cubic fit is within 2.7e-4 r).
    for (Eigen::Index i = 0; i < curve.value().points.rows(); ++i)
      EXPECT_NEAR(curve.value().points.row(i).norm(), 80.0, 80 * 3e-4);
  }
}

TEST(CurveJson, BezierNeedsThreePointsPerSegment) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("bad.json", R"({"bezier": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]})");
  EXPECT_TRUE(failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path,
                        "3 control points per segment"));
}

TEST(CurveJson, BezierHugeControlPoint) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "huge.json", R"({"bezier": [[0,0,0],[1e12,0,0],[1,1,0],[0,1,0],[0,2,0],[-1,1,0]]})");
  EXPECT_TRUE(
      failsWith(readCurve(path).status(), ErrorCode::InputInvalid, path, "control point 2"));
}

TEST(CurveJson, NotJson) {
  test::ScratchDir dir;
  const std::string path = dir.write("bad.json", "{\"points\": ");
  EXPECT_TRUE(
      failsWith(readCurve(path).status(), ErrorCode::InputUnreadable, path, "not valid JSON"));
}

TEST(CurveJson, ACurveSmallerThanAnOutlineMayBeIsRefused) {
  test::ScratchDir dir;
  // A seam 0.2 um across, as an outline that small is refused: nothing a sheet is cut to.
  const std::string tiny = dir.write(
      "tiny.json",
      R"({"points": [[0,0,0],[1e-4,0,1e-5],[1e-4,1e-4,0],[0,1e-4,1e-5],[-5e-5,5e-5,2e-5]]})");
  CurveReadOptions closed;
  closed.forceClosed = true;
  EXPECT_TRUE(failsWith(readCurve(tiny, closed).status(), ErrorCode::InputInvalid, tiny,
                        "mm across; seam curves must be at least 1 mm across"));
  // One just over the size is read.
  const std::string small = dir.write(
      "small.json", R"({"points": [[0,0,0],[0.8,0,0.1],[0.8,0.8,0],[0,0.8,0.1],[-0.4,0.4,0.2]]})");
  EXPECT_TRUE(readCurve(small, closed).isOk()) << readCurve(small, closed).status().message();
}

TEST(CurveJson, UnknownAndRepeatedKeysAreRefused) {
  test::ScratchDir dir;
  const std::string points = R"([[0,0,0],[10,0,1],[10,10,0],[0,10,1],[-5,5,2],[0,0,0]])";
  const std::string typo = dir.write("typo.json", "{\"points\": " + points + ", \"unit\": \"in\"}");
  EXPECT_TRUE(
      failsWith(readCurve(typo).status(), ErrorCode::InputInvalid, typo, "\"unit\": unknown key"));
  const std::string twice =
      dir.write("twice.json", "{\"points\": " + points + ", \"points\": " + points + "}");
  EXPECT_TRUE(failsWith(readCurve(twice).status(), ErrorCode::InputInvalid, twice,
                        "\"points\" is given twice in one object"));
}

TEST(CurveFiles, ANumberNoDoubleHoldsIsNamedForWhyItIsOutOfRange) {
  test::ScratchDir dir;
  for (const bool obj : {true, false}) {
    const auto write = [&](const std::string& number) {
      return obj ? dir.write("n.obj", "v 0 0 0\nv " + number +
                                          " 0 0\nv 1 1 0\nv 0 1 1\nv 2 2 2\nl 1 2 3 4 5 1\n")
                 : dir.write("n.json", "{\"points\": [[0, 0, 0], [" + number +
                                           ", 0, 0], [1, 1, 0], [0, 1, 1], [2, 2, 2]]}");
    };
    // Too small to hold: the reason is not that it is infinite.
    const std::string small = write("1e-999");
    const Status tooSmall = readCurve(small).status();
    EXPECT_TRUE(failsWith(tooSmall, ErrorCode::InputInvalid, small,
                          "'1e-999' is out of range (too close to zero to be held as a number: "
                          "write 0)"))
        << tooSmall.message();
    EXPECT_EQ(tooSmall.message().find("finite"), std::string::npos);
    const std::string large = write("-1e999");
    EXPECT_TRUE(failsWith(readCurve(large).status(), ErrorCode::InputInvalid, large,
                          "'-1e999' is out of range (too large for a number: coordinates must be "
                          "finite)"));
  }
}

}  // namespace
}  // namespace dform
