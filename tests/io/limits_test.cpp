// SPDX-License-Identifier: GPL-3.0-or-later
// Point limits (OutlineReadOptions::maxPoints, CurveReadOptions::maxPoints): a file with more
// points than the limit is refused with one line saying so, as soon as the reader knows, and a
// file at the limit is read. Small limits here stand for the default million.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dform/io/curve_reader.h"
#include "dform/io/outline_reader.h"
#include "test_util.h"

namespace dform {
namespace {

using test::failsWith;

/// n points of a saddle curve, as OBJ `v` lines or as JSON [x, y, z] items.
std::string saddle(int n, bool obj) {
  std::string text;
  char item[128];
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const double x = 50 * std::cos(t), y = 50 * std::sin(t), z = 10 * std::cos(2 * t);
    if (obj)
      std::snprintf(item, sizeof item, "v %.9f %.9f %.9f\n", x, y, z);
    else
      std::snprintf(item, sizeof item, "%s[%.9f, %.9f, %.9f]", i ? ", " : "", x, y, z);
    text += item;
  }
  return text;
}

std::string objCurve(int n) {
  std::string text = saddle(n, true) + "l";
  for (int i = 1; i <= n; ++i) text += " " + std::to_string(i);
  return text + " 1\n";
}

CurveReadOptions limitedTo(std::size_t maxPoints) {
  CurveReadOptions options;
  options.maxPoints = maxPoints;
  options.forceClosed = true;  // the JSON lists do not repeat their first point
  return options;
}

TEST(PointLimits, ObjCurveStopsAtTheVertexPastTheLimit) {
  EXPECT_TRUE(parseCurve(objCurve(100), "seam.obj", limitedTo(100)).isOk());
  // The 101st vertex is on line 101: the rest of the file is never parsed.
  EXPECT_TRUE(failsWith(parseCurve(objCurve(101), "seam.obj", limitedTo(100)).status(),
                        ErrorCode::InputInvalid, "seam.obj",
                        "line 101: more than 100 vertices (the limit)"));
}

TEST(PointLimits, ObjPolylineOverTheLimitIsRefused) {
  // Few vertices, but a polyline that runs round them many times.
  std::string text = saddle(10, true) + "l";
  for (int i = 0; i < 150; ++i) text += " " + std::to_string(i % 10 + 1);
  EXPECT_TRUE(failsWith(parseCurve(text + "\n", "seam.obj", limitedTo(100)).status(),
                        ErrorCode::InputInvalid, "seam.obj",
                        "line 11: more than 100 points in one element (the limit)"));
}

TEST(PointLimits, JsonCurve) {
  auto json = [](int n) { return "{\"points\": [" + saddle(n, false) + "]}"; };
  EXPECT_TRUE(parseCurve(json(300), "seam.json", limitedTo(300)).isOk());
  // One point past the limit: refused while it is parsed, by its numbers.
  EXPECT_TRUE(failsWith(parseCurve(json(301), "seam.json", limitedTo(300)).status(),
                        ErrorCode::InputInvalid, "seam.json",
                        "the file has more than 300 points (the limit)"));
  // Far more lists than the points could need: refused while parsing, before the tree is built.
  std::string empties = "[";
  for (int i = 0; i < 5000; ++i) empties += "[],";
  EXPECT_TRUE(failsWith(parseCurve(empties + "[]]", "seam.json", limitedTo(300)).status(),
                        ErrorCode::InputInvalid, "seam.json", "more JSON values"));
}

TEST(PointLimits, FlattenedBezierCurve) {
  const std::string circle =
      R"({"bezier": [[80, 0, 0], [80, 44, 10], [44, 80, 10], [0, 80, 0], [-44, 80, -10],
         [-80, 44, -10], [-80, 0, 0], [-80, -44, 10], [-44, -80, 10], [0, -80, 0],
         [44, -80, -10], [80, -44, -10]]})";
  const Result<Curve3> read = parseCurve(circle, "seam.json");
  ASSERT_TRUE(read.isOk()) << read.status().message();
  const std::size_t points = std::size_t(read.value().points.rows());
  EXPECT_TRUE(parseCurve(circle, "seam.json", limitedTo(points)).isOk());
  EXPECT_TRUE(failsWith(
      parseCurve(circle, "seam.json", limitedTo(points - 1)).status(), ErrorCode::InputInvalid,
      "seam.json",
      "the flattened curve has more than " + std::to_string(points - 1) + " points (the limit)"));
}

OutlineReadOptions outlineLimitedTo(std::size_t maxPoints) {
  OutlineReadOptions options;
  options.maxPoints = maxPoints;
  return options;
}

/// A regular n-gon of radius 50 as SVG polygon points or JSON [x, y] items.
std::string polygon(int n, bool svg) {
  std::string text;
  char item[96];
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    std::snprintf(item, sizeof item, svg ? "%s%.9f,%.9f" : "%s[%.9f, %.9f]",
                  i ? (svg ? " " : ", ") : "", 100 + 50 * std::cos(t), 100 + 50 * std::sin(t));
    text += item;
  }
  return text;
}

TEST(PointLimits, SvgOutlinesCountTogether) {
  auto svg = [](const std::string& body) {
    return "<svg xmlns='http://www.w3.org/2000/svg' width='200mm' height='200mm' "
           "viewBox='0 0 200 200'>" +
           body + "</svg>";
  };
  const std::string one = "<polygon points='" + polygon(100, true) + "'/>";
  EXPECT_TRUE(parseOutline(svg(one), "piece.svg", outlineLimitedTo(100)).isOk());
  // Stopped while the 101st command is recorded, before anything is flattened.
  EXPECT_TRUE(failsWith(parseOutline(svg("<polygon points='" + polygon(101, true) + "'/>"),
                                     "piece.svg", outlineLimitedTo(100))
                            .status(),
                        ErrorCode::InputInvalid, "piece.svg",
                        "polygon 1 brings the outlines to more than 100 points (the limit)"));
  // A hole's points count with the outline's.
  const std::string hole = "<rect x='90' y='90' width='20' height='20'/>";
  EXPECT_TRUE(failsWith(parseOutline(svg(one + hole), "piece.svg", outlineLimitedTo(100)).status(),
                        ErrorCode::InputInvalid, "piece.svg", "rect 1 brings the outlines"));
  // Commands that draw nothing take memory too.
  std::string moves = "<path d='";
  for (int i = 0; i < 150; ++i) moves += "M 1 1 ";
  EXPECT_TRUE(
      failsWith(parseOutline(svg(moves + "'/>"), "piece.svg", outlineLimitedTo(100)).status(),
                ErrorCode::InputInvalid, "piece.svg",
                "path 1 has more than 100 moveto and closepath commands (the limit)"));
  // A circle flattened finer than the limit allows.
  OutlineReadOptions fine = outlineLimitedTo(1000);
  fine.flattenTolerance = 1e-6;
  EXPECT_TRUE(
      failsWith(parseOutline(svg("<circle cx='100' cy='100' r='90'/>"), "piece.svg", fine).status(),
                ErrorCode::InputInvalid, "piece.svg",
                "more than 1000 points (the limit) at a flatten tolerance of 1e-06 mm"));
}

TEST(PointLimits, JsonOutlinesCountTogether) {
  const std::string outline = "[" + polygon(100, false) + "]";
  EXPECT_TRUE(
      parseOutline("{\"points\": " + outline + "}", "piece.json", outlineLimitedTo(100)).isOk());
  const std::string withHole =
      "{\"points\": " + outline + ", \"holes\": [[[95, 95], [105, 95], [100, 105]]]}";
  EXPECT_TRUE(failsWith(parseOutline(withHole, "piece.json", outlineLimitedTo(100)).status(),
                        ErrorCode::InputInvalid, "piece.json",
                        "the file has more than 100 points (the limit)"));
}

TEST(PointLimits, AJsonOutlineAloneIsHeldToTheLimitWhileItIsParsed) {
  // One point past the limit (as 1 000 001 against the default million), with no hole or crease
  // to count it with: refused, bare or in an object, before the point list is built.
  for (const std::string& text :
       {"[" + polygon(101, false) + "]", "{\"points\": [" + polygon(101, false) + "]}"})
    EXPECT_TRUE(failsWith(parseOutline(text, "piece.json", outlineLimitedTo(100)).status(),
                          ErrorCode::InputInvalid, "piece.json",
                          "the file has more than 100 points (the limit)"));
  // Numbers past the limit end the parse where they pass it: the rest is never read.
  const std::string broken = "[" + polygon(101, false) + ", [1, 2], this is not JSON";
  EXPECT_TRUE(failsWith(parseOutline(broken, "piece.json", outlineLimitedTo(100)).status(),
                        ErrorCode::InputInvalid, "piece.json", "more than 100 points"));
}

}  // namespace
}  // namespace dform
