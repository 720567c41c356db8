// SPDX-License-Identifier: GPL-3.0-or-later
// Every bad outline input gives the documented ErrorCode and a one-line message naming the file.
#include <gtest/gtest.h>

#include <filesystem>

#include "dform/io/outline_reader.h"
#include "test_util.h"

namespace dform {
namespace {

using test::failsWith;

std::string svg(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' width='200mm' height='200mm' viewBox='0 0 200 "
         "200'>" +
         body + "</svg>";
}

TEST(OutlineErrors, MissingFile) {
  test::ScratchDir dir;
  const std::string path = dir.path() + "/nothing.svg";
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "no such file"));
}

TEST(OutlineErrors, FolderInsteadOfFile) {
  test::ScratchDir dir;
  EXPECT_TRUE(failsWith(readOutline(dir.path()).status(), ErrorCode::InputUnreadable, dir.path(),
                        "folder"));
}

TEST(OutlineErrors, FileTooLarge) {
  test::ScratchDir dir;
  const std::string path = dir.write("huge.svg", "");
  std::filesystem::resize_file(path, (std::uintmax_t(64) << 20) + 1);  // sparse: nothing is written
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "too large"));
}

TEST(OutlineErrors, NotSvgOrJson) {
  test::ScratchDir dir;
  const std::string path = dir.write("notes.txt", "just some notes\n");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path,
                        "not an SVG or JSON file"));
  const std::string binary = dir.write("picture.png", std::string("\x89PNG\r\n\x1a\n\0\0", 10));
  EXPECT_TRUE(failsWith(readOutline(binary).status(), ErrorCode::InputUnreadable, binary));
}

TEST(OutlineErrors, SvgThatIsNotXml) {
  test::ScratchDir dir;
  const std::string path = dir.write("text.svg", "this is not xml");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path));
}

TEST(OutlineErrors, MalformedXml) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("broken.svg", "<svg xmlns='http://www.w3.org/2000/svg'><rect width='10'</svg>");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path,
                        "not well-formed XML"));
}

TEST(OutlineErrors, XmlThatIsNotSvg) {
  test::ScratchDir dir;
  const std::string path = dir.write("page.svg", "<html><body/></html>");
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "no <svg> root"));
}

TEST(OutlineErrors, MalformedPathData) {
  test::ScratchDir dir;
  const std::string path = dir.write("bad-d.svg", svg("<path d='M 0 0 L 10 x 20 Z'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "path 1"));
}

TEST(OutlineErrors, MalformedViewBox) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("bad-vb.svg", "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 wide'/>");
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "viewBox"));
}

TEST(OutlineErrors, DeepNestingRefused) {
  test::ScratchDir dir;
  std::string body;
  for (int i = 0; i < 100000; ++i) body += "<g>";
  for (int i = 0; i < 100000; ++i) body += "</g>";
  const std::string path = dir.write("deep.svg", svg(body));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputUnreadable, path, "nested"));
}

TEST(OutlineErrors, NoClosedOutline) {
  test::ScratchDir dir;
  const std::string path = dir.write("empty.svg", svg("<text x='1' y='1'>nothing to cut</text>"));
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "no closed outline"));
}

TEST(OutlineErrors, OpenPathSaysHowFarItsEndsAre) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("open.svg",
                svg("<rect x='150' width='10' height='10'/><path d='M10 10 H50 V50 H10 V13.2'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "path 1 is open (its end is 3.2 mm from its start)"));
}

TEST(OutlineErrors, OpenSubpathIsNamed) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("open2.svg", svg("<path d='M10 10 H90 V90 H10 Z M20 20 H30 V30'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "path 1 (subpath 2) is open"));
}

TEST(OutlineErrors, OpenPolyline) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("polyline.svg", svg("<polyline id='cut\nout' points='10,10 90,10 90,90 10,90'/>"));
  // The id's line break does not break the one-line message.
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "polyline 1 (id \"cut out\") is open"));
}

TEST(OutlineErrors, LineIsOpen) {
  test::ScratchDir dir;
  const std::string path = dir.write("line.svg", svg("<line x1='0' y1='0' x2='10' y2='0'/>"));
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "line 1 is open"));
}

TEST(OutlineErrors, SelfIntersectingSaysWhere) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("bowtie.svg", svg("<polygon points='0,0 100,100 100,0 0,100'/>"));
  // The crossing is at (50, 50) in the SVG and at (50, 200 - 50) in the y-up page frame.
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "crosses itself near (50, 150) mm"));
}

TEST(OutlineErrors, InfiniteCoordinate) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("inf.svg", svg("<path transform='scale(1e300)' d='M0 0 L1e300 0 L0 1e300 Z'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "infinite"));
}

TEST(OutlineErrors, NonFiniteNumbersInAttributesAreInvalidNotUnreadable) {
  // SVG's number grammar has no NaN or infinity, but such a value is a coordinate that is not
  // finite (bad content, README exit 4), not a misspelt one (an unreadable file, exit 3).
  test::ScratchDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {svg("<polygon points='10,10 NaN,100 100,10'/>"),
       "polygon 1 has a non-finite number 'NaN' in its 'points'"},
      {svg("<rect x='inf' y='10' width='100' height='100'/>"), "'inf' in its 'x'"},
      {svg("<path d='M 10 10 L 1e999 100 L 100 10 Z'/>"), "'1e999' in its 'd'"},
      {svg("<circle cx='100' cy='100' r='-nan'/>"), "'-nan' in its 'r'"},
      {svg("<rect width='100' height='100' transform='translate(NaN 0)'/>"), "in its 'transform'"},
      {"<svg xmlns='http://www.w3.org/2000/svg' width='NaNmm' height='200mm'><rect width='9' "
       "height='9'/></svg>",
       "'NaNmm' in its 'width'"},
      {"<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 inf 200'><rect width='9' "
       "height='9'/></svg>",
       "'inf' in its 'viewBox'"}};
  for (const auto& [text, says] : cases) {
    const std::string path = dir.write("nonfinite.svg", text);
    EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, says)) << text;
  }
  const std::string misspelt =
      dir.write("misspelt.svg", svg("<polygon points='10,10 abc,100 100,10'/>"));
  EXPECT_TRUE(failsWith(readOutline(misspelt).status(), ErrorCode::InputUnreadable, misspelt,
                        "malformed 'points'"));
}

TEST(OutlineErrors, HugeCoordinate) {
  test::ScratchDir dir;
  const std::string path = dir.write("huge.svg", svg("<rect width='2e7' height='10'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "too large"));
  OutlineReadOptions tight;
  tight.maxCoordinate = 100;
  const std::string small = dir.write("small.svg", svg("<rect width='150' height='10'/>"));
  EXPECT_TRUE(failsWith(readOutline(small, tight).status(), ErrorCode::InputInvalid, small,
                        "rect 1 has a coordinate"));
}

TEST(OutlineErrors, FewerThanThreeDistinctPoints) {
  test::ScratchDir dir;
  const std::string path = dir.write("two.svg", svg("<polygon points='10,10 50,50 10,10'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "fewer than 3 distinct points"));
}

TEST(OutlineErrors, ZeroArea) {
  test::ScratchDir dir;
  const std::string path = dir.write("flat.svg", svg("<polygon points='10,10 50,10 90,10'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "zero area"));
}

TEST(OutlineErrors, TwoSeparateOutlines) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("two-pieces.svg", svg("<rect x='10' y='10' width='50' height='50'/>"
                                      "<circle cx='120' cy='40' r='20'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "2 separate outlines; expected one piece"));
}

TEST(OutlineErrors, IslandInsideHoleIsASeparatePiece) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("island.svg", svg("<rect x='10' y='10' width='180' height='180'/>"
                                  "<rect x='40' y='40' width='120' height='120'/>"
                                  "<rect x='80' y='80' width='40' height='40'/>"));
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "2 separate outlines"));
}

TEST(OutlineErrors, OverlappingOutlines) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("overlap.svg", svg("<rect x='10' y='10' width='100' height='100'/>"
                                   "<circle cx='110' cy='60' r='20'/>"));
  EXPECT_TRUE(
      failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "touch or cross"));
  // Side by side, sharing the edge x = 50: they touch somewhere on it.
  const std::string touching = dir.write(
      "touching.svg", svg("<rect width='50' height='50'/><rect x='50' width='50' height='50'/>"));
  EXPECT_TRUE(failsWith(readOutline(touching).status(), ErrorCode::InputInvalid, touching,
                        "touch or cross near (50, "));
}

TEST(OutlineErrors, NegativeRadius) {
  test::ScratchDir dir;
  const std::string path = dir.write("neg.svg", svg("<circle cx='50' cy='50' r='-5'/>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path,
                        "circle 1 has a negative 'r'"));
}

TEST(OutlineErrors, NestedSvgUnsupported) {
  test::ScratchDir dir;
  const std::string path =
      dir.write("nested.svg", svg("<svg x='10'><rect width='10' height='10'/></svg>"));
  EXPECT_TRUE(failsWith(readOutline(path).status(), ErrorCode::InputInvalid, path, "nested <svg>"));
}

TEST(OutlineErrors, AbsurdToleranceIsRefusedNotHung) {
  test::ScratchDir dir;
  OutlineReadOptions options;
  options.flattenTolerance = 1e-12;
  const std::string path = dir.write("circle.svg", svg("<circle cx='100' cy='100' r='90'/>"));
  EXPECT_TRUE(failsWith(readOutline(path, options).status(), ErrorCode::InputInvalid, path,
                        "flatten tolerance"));
  options.flattenTolerance = 0;
  EXPECT_TRUE(failsWith(readOutline(path, options).status(), ErrorCode::Usage, path));
}

TEST(OutlineErrors, TruncatedAndCorruptedFilesNeverCrash) {
  // Every prefix of a valid file, and the file with bytes overwritten, reads as a Status: ok or
  // an error naming the file, never a crash or an exception.
  test::ScratchDir dir;
  const std::string text =
      svg("<g transform='rotate(10)'><path d='M10 10 C 50 0 90 40 90 90 A 40 40 0 0 1 10 90 Z'/>"
          "<circle cx='50' cy='60' r='10'/></g>");
  for (std::size_t cut = 0; cut < text.size(); cut += 3) {
    const std::string path = dir.write("cut.svg", text.substr(0, cut));
    const Result<Shape2> shape = readOutline(path);
    if (!shape.isOk()) {
      EXPECT_EQ(shape.status().message().rfind(path + ": ", 0), 0u) << shape.status().message();
    }
  }
  for (std::size_t at = 0; at < text.size(); at += 2) {
    std::string corrupted = text;
    corrupted[at] = "<>/\"'0-.e "[at % 10];
    const std::string path = dir.write("corrupt.svg", corrupted);
    const Result<Shape2> shape = readOutline(path);
    if (!shape.isOk()) {
      EXPECT_EQ(shape.status().message().rfind(path + ": ", 0), 0u) << shape.status().message();
    }
  }
}

}  // namespace
}  // namespace dform
