// SPDX-License-Identifier: GPL-3.0-or-later
// JSON outlines: object and bare-array forms, units, holes, and malformed files.
#include <gtest/gtest.h>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "test_util.h"

namespace dform {
namespace {

using test::failsWith;

TEST(JsonOutline, ObjectWithUnitsAndHole) {
  test::ScratchDir dir;
  // Drawn clockwise with a repeated closing point; the hole is counter-clockwise already.
  const std::string path = dir.write("piece.json", R"({
    "units": "cm",
    "points": [[0, 0], [0, 5], [10, 5], [10, 0], [0, 0]],
    "holes": [[[2, 1], [4, 1], [4, 3]]]
  })");
  const Result<Shape2> shape = readOutline(path);
  ASSERT_TRUE(shape.isOk()) << shape.status().message();
  const Points2& P = shape.value().outer.points;
  EXPECT_EQ(P.rows(), 4);
  EXPECT_NEAR(closedLength(P), 300.0, 1e-12);
  EXPECT_NEAR(signedArea(P), 5000.0, 1e-9);  // made counter-clockwise
  // ... about the point it was drawn from, which stays first: start fractions count from there.
  EXPECT_EQ(P.row(0), Eigen::RowVector2d(0, 0));
  EXPECT_EQ(P.row(1), Eigen::RowVector2d(100, 0));
  ASSERT_EQ(shape.value().holes.size(), 1u);
  EXPECT_NEAR(signedArea(shape.value().holes[0].points), 200.0, 1e-9);
  EXPECT_EQ(shape.value().outer.source, path);
}

TEST(JsonOutline, BareArrayIsMillimetres) {
  test::ScratchDir dir;
  const std::string path = dir.write("bare.json", "[[0,0],[100,0],[100,50],[0,50]]");
  const Result<Shape2> shape = readOutline(path);
  ASSERT_TRUE(shape.isOk()) << shape.status().message();
  EXPECT_NEAR(closedLength(shape.value().outer.points), 300.0, 1e-12);
}

TEST(JsonOutline, InchesAndContentSniffedWithoutExtension) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("outline", R"({"units": "in", "points": [[0,0],[1,0],[1,1],[0,1]]})");
  const Result<Shape2> shape = readOutline(path);
  ASSERT_TRUE(shape.isOk()) << shape.status().message();
  EXPECT_NEAR(closedLength(shape.value().outer.points), 4 * 25.4, 1e-12);
}

TEST(JsonOutline, NotJson) {
  test::ScratchDir dir;
  const std::string path = dir.write("bad.json", "{\"points\": [[0,0], [1,");
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "not valid JSON"));
}

TEST(JsonOutline, WrongStructure) {
  test::ScratchDir dir;
  const std::string noPoints = dir.write("nopoints.json", R"({"outline": []})");
  EXPECT_TRUE(failsWith(readOutline(noPoints).status(), ErrorCode::InputUnreadable, noPoints,
                        "\"points\""));
  const std::string triple = dir.write("triple.json", R"({"points": [[0,0],[1,0,0],[1,1]]})");
  EXPECT_TRUE(
      failsWith(readOutline(triple).status(), ErrorCode::InputUnreadable, triple, "point 2"));
  const std::string text = dir.write("text.json", R"([[0,0],["1",0],[1,1]])");
  EXPECT_TRUE(failsWith(readOutline(text).status(), ErrorCode::InputUnreadable, text, "point 2"));
  const std::string holes =
      dir.write("holes.json", R"({"points": [[0,0],[1,0],[1,1]], "holes": 3})");
  EXPECT_TRUE(failsWith(readOutline(holes).status(), ErrorCode::InputUnreadable, holes, "holes"));
}

TEST(JsonOutline, UnknownAndRepeatedKeysAreRefused) {
  test::ScratchDir dir;
  // A misspelt key would drop what it holds without a word: the creases, the holes.
  const std::string square = "[[0,0],[100,0],[100,100],[0,100]]";
  for (const char* key : {"creaess", "hole", "Points", "unit"}) {
    const std::string path = dir.write(
        "typo.json", "{\"points\": " + square + ", \"" + key + "\": [[[10,10],[90,90]]]}");
    EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                          "\"" + std::string(key) + "\": unknown key"))
        << readOutline(path).status().message();
  }
  // The last of two would be kept silently.
  const std::string twice =
      dir.write("twice.json", "{\"points\": " + square + ", \"units\": \"mm\", \"units\": \"in\"}");
  EXPECT_TRUE(failsWith(readOutline(twice).status(), ErrorCode::InputInvalid, twice,
                        "\"units\" is given twice in one object"));
  const std::string inner =
      dir.write("inner.json", "[[0,0],[100,0],[100,100],[0,100], {\"x\": 1, \"x\": 2}]");
  EXPECT_TRUE(failsWith(readOutline(inner).status(), ErrorCode::InputInvalid, inner,
                        "\"x\" is given twice"));
  // Every key the format has is still read.
  const std::string all = dir.write(
      "all.json", "{\"points\": " + square +
                      ", \"units\": \"mm\", \"holes\": [[[40,40],[60,40],[60,60],[40,60]]], "
                      "\"creases\": []}");
  EXPECT_TRUE(readOutline(all).isOk()) << readOutline(all).status().message();
}

TEST(JsonOutline, UnknownUnits) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("furlong.json", R"({"units": "furlong", "points": [[0,0],[1,0],[1,1]]})");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "units"));
}

TEST(JsonOutline, HugeNumber) {
  test::ScratchDir dir;
  const std::string path = dir.write("huge.json", "[[0,0],[1e9,0],[0,1]]");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "the outline has a coordinate that is too large"));
}

TEST(JsonOutline, SelfIntersecting) {
  test::ScratchDir dir;
  const std::string path = dir.write("bowtie.json", "[[0,0],[10,10],[10,0],[0,10]]");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "crosses itself near (5, 5) mm"));
}

TEST(JsonOutline, HoleOutsideIsASecondOutline) {
  test::ScratchDir dir;
  const std::string path = dir.write("outside.json", R"({"points": [[0,0],[10,0],[10,10],[0,10]],
                                                           "holes": [[[20,0],[30,0],[30,10]]]})");
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "2 separate outlines"));
}

TEST(JsonOutline, TooFewPoints) {
  test::ScratchDir dir;
  const std::string path = dir.write("two.json", "[[0,0],[10,0]]");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "fewer than 3 distinct points"));
}

TEST(JsonOutline, DeeplyNestedJsonDoesNotCrash) {
  test::ScratchDir dir;
  const int depth = 200000;
  const std::string nested = std::string(depth, '[') + std::string(depth, ']');
  const std::string path = dir.write("deep.json", nested);
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "point 1"));
  const std::string units =
      dir.write("units.json", R"({"points": [[0,0],[1,0],[1,1]], "units": )" + nested + "}");
  EXPECT_TRUE(failsWith(readOutline(units).status(), ErrorCode::InputUnreadable, units, "units"));
}

}  // namespace
}  // namespace dform
