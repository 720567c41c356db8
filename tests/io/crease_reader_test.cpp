// SPDX-License-Identifier: GPL-3.0-or-later
// Crease lines: how they are marked in SVG and JSON, clipped to the piece, snapped onto its
// boundary, and every way a crease can be drawn wrong.
#include <gtest/gtest.h>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "test_util.h"

namespace dform {
namespace {

// A 100 x 100 mm page (1 user unit = 1 mm, y down); the page frame has y up: y' = 100 - y.
std::string page(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' "
         "xmlns:inkscape='http://www.inkscape.org/namespaces/inkscape' width='100mm' "
         "height='100mm' "
         "viewBox='0 0 100 100'>\n" +
         body + "\n</svg>\n";
}

const char* kSquare = "<rect x='10' y='10' width='80' height='80'/>";  // page frame: 10..90

Shape2 readCreasedOk(const std::string& path) {
  Result<Shape2> shape = readOutline(path);
  EXPECT_TRUE(shape.isOk()) << shape.status().message();
  return shape.isOk() ? shape.value() : Shape2{};
}

Eigen::RowVector2d end(const CreaseLine& c, bool last) {
  return c.points.row(last ? c.points.rows() - 1 : 0);
}

TEST(CreaseReader, ClassMarksACreaseAndItsEndsStayOnTheOutline) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "a.svg", page(std::string(kSquare) + "<path class='fold crease' d='M 10 50 L 90 50'/>"));
  const Shape2 shape = readCreasedOk(path);
  ASSERT_EQ(shape.creases.size(), 1u);
  EXPECT_EQ(shape.creases[0].points.rows(), 2);
  EXPECT_NEAR((end(shape.creases[0], false) - Eigen::RowVector2d(10, 50)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((end(shape.creases[0], true) - Eigen::RowVector2d(90, 50)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(closedLength(shape.outer.points), 320.0, 1e-9);  // the outline is unchanged
  EXPECT_TRUE(shape.holes.empty());
}

TEST(CreaseReader, InkscapeLayerLabelledCreasesHoldsCurvedCreases) {
  test::ScratchDir dir;
  // A quarter circle of radius 40 about the corner (10, 10) of the page (page frame (10, 90)),
  // from (50, 10) to (10, 50): both ends on the square's edges.
  const std::string body = std::string(kSquare) +
                           "<g inkscape:groupmode='layer' inkscape:label='Creases'>"
                           "<path d='M 50 10 A 40 40 0 0 1 10 50'/></g>";
  const Shape2 shape = readCreasedOk(dir.write("a.svg", page(body)));
  ASSERT_EQ(shape.creases.size(), 1u);
  EXPECT_GT(shape.creases[0].points.rows(), 10);  // flattened
  EXPECT_NEAR(openLength(shape.creases[0].points), 0.5 * M_PI * 40.0, 0.05);
  for (Eigen::Index i = 0; i < shape.creases[0].points.rows(); ++i)
    EXPECT_NEAR((shape.creases[0].points.row(i) - Eigen::RowVector2d(10, 90)).norm(), 40.0, 0.02);
}

TEST(CreaseReader, UnmarkedOpenPathIsStillAnError) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("a.svg", page(std::string(kSquare) + "<path d='M 10 50 L 90 50'/>"));
  EXPECT_TRUE(
      test::failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "is open"));
}

TEST(CreaseReader, LineDrawnAcrossTheOutlineIsClippedToThePiece) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "a.svg",
      page(std::string(kSquare) + "<line class='crease' x1='0' y1='30' x2='100' y2='70'/>"));
  const Shape2 shape = readCreasedOk(path);
  ASSERT_EQ(shape.creases.size(), 1u);
  // y' = 70 - 0.4 x crosses x = 10 at y' = 66 and x = 90 at y' = 34.
  EXPECT_NEAR((end(shape.creases[0], false) - Eigen::RowVector2d(10, 66)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((end(shape.creases[0], true) - Eigen::RowVector2d(90, 34)).norm(), 0.0, 1e-9);
}

TEST(CreaseReader, EndsShortOfTheOutlineBySubMillimetreSnapOntoIt) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "a.svg",
      page(std::string(kSquare) + "<line class='crease' x1='10.6' y1='50' x2='89.3' y2='50'/>"));
  const Shape2 shape = readCreasedOk(path);
  ASSERT_EQ(shape.creases.size(), 1u);
  EXPECT_NEAR((end(shape.creases[0], false) - Eigen::RowVector2d(10, 50)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((end(shape.creases[0], true) - Eigen::RowVector2d(90, 50)).norm(), 0.0, 1e-12);
}

TEST(CreaseReader, ACreaseAcrossAHoleBecomesTwoCreases) {
  test::ScratchDir dir;
  const std::string body = std::string(kSquare) + "<circle cx='50' cy='50' r='15'/>" +
                           "<line class='crease' x1='10' y1='50' x2='90' y2='50'/>";
  const Shape2 shape = readCreasedOk(dir.write("a.svg", page(body)));
  ASSERT_EQ(shape.holes.size(), 1u);
  ASSERT_EQ(shape.creases.size(), 2u);
  // Each part runs from the outline to the hole: 25 mm long, within the flattening tolerance.
  for (const CreaseLine& c : shape.creases) {
    EXPECT_NEAR(openLength(c.points), 25.0, 0.02);
    EXPECT_NE(c.label.find("part"), std::string::npos) << c.label;
  }
}

TEST(CreaseReader, JsonCreasesInTheirUnits) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "a.json",
      R"({"units": "cm", "points": [[0,0],[8,0],[8,8],[0,8]], "creases": [[[0,0],[8,8]]]})");
  const Shape2 shape = readCreasedOk(path);
  ASSERT_EQ(shape.creases.size(), 1u);
  EXPECT_NEAR(openLength(shape.creases[0].points), 80.0 * std::sqrt(2.0), 1e-9);
}

TEST(CreaseReader, CreasesMayShareAnEndOnTheBoundary) {
  test::ScratchDir dir;
  const std::string body = std::string(kSquare) +
                           "<g class='crease'><line x1='10' y1='10' x2='90' y2='50'/>"
                           "<line x1='10' y1='90' x2='90' y2='50'/></g>";
  EXPECT_EQ(readCreasedOk(dir.write("a.svg", page(body))).creases.size(), 2u);
}

TEST(CreaseReader, BadCreasesAreNamedErrors) {
  test::ScratchDir dir;
  struct Case {
    const char* name;
    std::string body;
    const char* message;
  };
  const std::vector<Case> cases = {
      {"inside.svg", "<line class='crease' x1='10' y1='50' x2='60' y2='50'/>", "inside the piece"},
      {"outside.svg", "<line class='crease' x1='0' y1='5' x2='100' y2='5'/>",
       "lies outside the piece"},
      {"closed.svg", "<circle class='crease' cx='50' cy='50' r='10'/>", "closed crease"},
      {"crossing.svg",
       "<line class='crease' x1='10' y1='50' x2='90' y2='50'/><line class='crease' x1='50' y1='10' "
       "x2='50' y2='90'/>",
       "cross near (50, 50)"},
      {"self.svg", "<path class='crease' d='M 10 20 L 80 80 L 80 20 L 10 80'/>", "crosses itself"},
      {"dot.svg", "<path class='crease' d='M 10 50 L 10 50'/>", "its ends meet"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write(c.name, page(std::string(kSquare) + c.body));
    EXPECT_TRUE(
        test::failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, c.message))
        << c.name;
  }
  const std::string dot =
      dir.write("dot.json", R"({"points": [[0,0],[8,0],[8,8]], "creases": [[[0,0],[0,0]]]})");
  EXPECT_TRUE(test::failsWith(readOutline(dot).status(), ErrorCode::InputInvalid, dot,
                              "fewer than 2 distinct points"));
  const std::string nan =
      dir.write("nan.json", R"({"points": [[0,0],[8,0],[8,8]], "creases": [[[0,0],[1e300,1]]]})");
  EXPECT_TRUE(
      test::failsWith(readOutline(nan).status(), ErrorCode::InputInvalid, nan, "too large"));
}

}  // namespace
}  // namespace dform
