// SPDX-License-Identifier: GPL-3.0-or-later
// The in-memory entries (makeDForm, makePieces): shapes and curves that never were files give the
// same D-Form as the files that hold them, and their messages name the pieces without a path.
#include <gtest/gtest.h>

#include <cmath>

#include "dform/core/polyline.h"
#include "dform/io/curve_reader.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "shipped_samples.h"

namespace dform {
namespace {

// An ellipse with semi-axes a and b, counter-clockwise, n points.
Shape2 ellipse(double a, double b, int n) {
  Shape2 shape;
  shape.outer.points.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    shape.outer.points.row(i) << a * std::cos(t), b * std::sin(t);
  }
  return shape;
}

TEST(InMemory, ShapesGiveTheDFormTheirFilesGive) {
  ForwardJob job;
  job.pieceA = test::samplePath("forward/ellipses-a.svg");
  job.pieceB = test::samplePath("forward/ellipses-b.svg");
  job.resolution = 60;
  MessageSink fileSink, memorySink;
  const Result<ForwardRun> fromFiles = runForward(job, fileSink);
  Result<Shape2> a = readOutline(job.pieceA), b = readOutline(job.pieceB);
  ASSERT_TRUE(fromFiles.isOk() && a.isOk() && b.isOk()) << fromFiles.status().message();
  const ForwardSettings& settings = job;
  const Result<ForwardRun> fromMemory = makeDForm(a.value(), b.value(), settings, memorySink);
  ASSERT_TRUE(fromMemory.isOk()) << fromMemory.status().message();
  EXPECT_EQ(fromMemory.value().modelUsed.name, fromFiles.value().modelUsed.name);
  // The same solve on the same numbers: bit for bit.
  EXPECT_EQ(fromMemory.value().model.a.shape, fromFiles.value().model.a.shape);
  EXPECT_EQ(fromMemory.value().model.b.flat, fromFiles.value().model.b.flat);
  EXPECT_EQ(fromMemory.value().metrics.lengthErrorMax, fromFiles.value().metrics.lengthErrorMax);
}

TEST(InMemory, PiecesWithoutAFileAreNamedByTheirRole) {
  ForwardSettings settings;
  settings.resolution = 40;
  MessageSink sink;
  // Perimeters 2 pi r: 40 and 45 mm radii differ by 11 %.
  const Result<ForwardRun> unequal =
      makeDForm(ellipse(40, 40, 400), ellipse(45, 45, 400), settings, sink);
  ASSERT_FALSE(unequal.isOk());
  EXPECT_EQ(unequal.status().code(), ErrorCode::InputInvalid);
  EXPECT_EQ(unequal.status().message().rfind("piece A and piece B: the perimeters differ", 0), 0u)
      << unequal.status().message();

  settings.fitPerimeter = true;  // B scaled to A: the D-Form of two equal circles
  const Result<ForwardRun> fitted =
      makeDForm(ellipse(40, 40, 400), ellipse(45, 45, 400), settings, sink);
  ASSERT_TRUE(fitted.isOk()) << fitted.status().message();
  EXPECT_NEAR(fitted.value().scaleB, 40.0 / 45.0, 1e-9);
  EXPECT_NEAR(fitted.value().metrics.seamLengthAMm, fitted.value().metrics.seamLengthBMm, 1e-9);
  // Each piece is named once in its line ("piece A: outline ..."), never "piece A (piece A)":
  // both runs into this sink name both pieces.
  int named = 0;
  for (const Message& m : sink.messages()) {
    EXPECT_EQ(m.text.find("(piece "), std::string::npos) << m.text;
    named += m.text.rfind("piece A: outline", 0) == 0 || m.text.rfind("piece B: outline", 0) == 0;
  }
  EXPECT_EQ(named, 4);
}

TEST(InMemory, ACurveGivesThePiecesItsFileGives) {
  InverseJob job;
  job.curve = test::samplePath("inverse/tennis-ball.obj");
  job.resolution = 60;
  MessageSink fileSink, memorySink;
  const Result<InverseRun> fromFile = runInverse(job, fileSink);
  Result<Curve3> curve = readCurve(job.curve);
  ASSERT_TRUE(fromFile.isOk() && curve.isOk()) << fromFile.status().message();
  curve.value().source.clear();  // as a curve made in memory
  const InverseSettings& settings = job;
  const Result<InverseRun> fromMemory = makePieces(curve.value(), settings, memorySink);
  ASSERT_TRUE(fromMemory.isOk()) << fromMemory.status().message();
  EXPECT_EQ(fromMemory.value().model.a.flat, fromFile.value().model.a.flat);
  EXPECT_EQ(fromMemory.value().curveMatch.curveError, fromFile.value().curveMatch.curveError);

  InverseSettings tooFine = settings;
  tooFine.resolution = 3;
  const Result<InverseRun> refused = makePieces(curve.value(), tooFine, memorySink);
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().code(), ErrorCode::Usage);
}

// A JSON outline file's text holding `P`, every coordinate exact.
std::string jsonOutline(const Points2& P) {
  std::string text = "[";
  char number[64];
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    std::snprintf(number, sizeof number, "%s[%.17g, %.17g]", i ? ", " : "", P(i, 0), P(i, 1));
    text += number;
  }
  return text + "]";
}

TEST(InMemory, ABadShapeIsRefusedAsItsFileIs) {
  // Each outline as a piece in memory and as a JSON file of the same name: the same code and the
  // same message, from makeDForm as from the reader (and never a memory estimate of NaN vertices).
  Points2 square(4, 2), bowtie(4, 2), halfMm(4, 2), twoPoints(2, 2), repeated(6, 2);
  square << 0, 0, 100, 0, 100, 100, 0, 100;
  bowtie << 0, 0, 100, 100, 100, 0, 0, 100;
  halfMm << 0, 0, 0.35, 0, 0.35, 0.35, 0, 0.35;
  twoPoints << 0, 0, 100, 0;
  repeated << 0, 0, 0, 0, 100, 0, 100, 0, 100, 0, 0, 0;
  const Shape2 other = ellipse(50, 50, 400);
  ForwardSettings settings;
  settings.resolution = 40;
  for (const Points2& outline : {Points2(0, 2), twoPoints, repeated, halfMm, bowtie}) {
    SCOPED_TRACE(jsonOutline(outline));
    Shape2 piece;
    piece.outer = {outline, "piece.json"};
    MessageSink sink;
    const Result<ForwardRun> made = makeDForm(piece, other, settings, sink);
    const Result<Shape2> read = parseOutline(jsonOutline(outline), "piece.json");
    ASSERT_FALSE(read.isOk());
    ASSERT_FALSE(made.isOk());
    EXPECT_EQ(made.status().code(), read.status().code());
    EXPECT_EQ(made.status().message(), read.status().message());
  }
  // No file holds a NaN; in memory it is the reader's bad coordinate, and an unnamed piece is
  // named by its role.
  Shape2 nan = ellipse(50, 50, 400);
  nan.outer.points(7, 1) = std::nan("");
  MessageSink sink;
  const Result<ForwardRun> made = makeDForm(other, nan, settings, sink);
  ASSERT_FALSE(made.isOk());
  EXPECT_EQ(made.status().code(), ErrorCode::InputInvalid);
  EXPECT_EQ(made.status().message().rfind("piece B: the outline has a coordinate that ", 0), 0u)
      << made.status().message();
  // A hole outside its outline, and a crease that stops in the middle of the piece.
  Shape2 holed = ellipse(50, 50, 400);
  holed.holes.push_back({Points2(square.array() + 200.0), ""});
  const Result<ForwardRun> apart = makeDForm(holed, other, settings, sink);
  ASSERT_FALSE(apart.isOk());
  EXPECT_EQ(apart.status().message(), "piece A: 2 separate outlines; expected one piece");
  Shape2 creased = ellipse(50, 50, 400);
  Points2 shortCrease(2, 2);
  shortCrease << -50, 0, 10, 0;
  creased.creases.push_back({shortCrease, ""});
  const Result<ForwardRun> shortened = makeDForm(creased, other, settings, sink);
  ASSERT_FALSE(shortened.isOk());
  EXPECT_EQ(shortened.status().code(), ErrorCode::InputInvalid);
  EXPECT_EQ(shortened.status().message().rfind("piece A: crease 1 ends 40 mm inside the piece", 0),
            0u)
      << shortened.status().message();
  Points2 outside(3, 2);
  outside << -50, 0, 55, 0, 55, 10;
  creased.creases = {{outside, "fold"}};
  const Result<ForwardRun> leaving = makeDForm(creased, other, settings, sink);
  ASSERT_FALSE(leaving.isOk());
  EXPECT_EQ(leaving.status().message().rfind("piece A: crease fold leaves the piece near", 0), 0u)
      << leaving.status().message();
}

TEST(InMemory, AClockwiseShapeIsTurnedAsItsFileIs) {
  Shape2 clockwise = ellipse(60, 40, 300);
  clockwise.outer.points = clockwise.outer.points.colwise().reverse().eval();
  const Result<Shape2> checked = checkOutline(clockwise, "piece A");
  const Result<Shape2> read = parseOutline(jsonOutline(clockwise.outer.points), "piece A");
  ASSERT_TRUE(checked.isOk() && read.isOk()) << checked.status().message();
  EXPECT_EQ(checked.value().outer.points, read.value().outer.points);
  EXPECT_LT(signedArea(clockwise.outer.points), 0.0);
  EXPECT_GT(signedArea(checked.value().outer.points), 0.0);
}

TEST(InMemory, AShapeReadFromAFilePassesItsCheckUnchanged) {
  // A shape with drawn creases (the Squaricle's disc) and one with a hole (the anti D-Form's).
  for (const char* name : {"forward/squaricle-disc.svg", "forward/anti-b.svg"}) {
    SCOPED_TRACE(name);
    const Result<Shape2> read = readOutline(test::samplePath(name));
    ASSERT_TRUE(read.isOk()) << read.status().message();
    const Result<Shape2> checked = checkOutline(read.value(), name);
    ASSERT_TRUE(checked.isOk()) << checked.status().message();
    EXPECT_EQ(checked.value().outer.points, read.value().outer.points);
    ASSERT_EQ(checked.value().holes.size(), read.value().holes.size());
    for (std::size_t k = 0; k < read.value().holes.size(); ++k)
      EXPECT_EQ(checked.value().holes[k].points, read.value().holes[k].points);
    ASSERT_EQ(checked.value().creases.size(), read.value().creases.size());
    for (std::size_t k = 0; k < read.value().creases.size(); ++k)
      EXPECT_EQ(checked.value().creases[k].points, read.value().creases[k].points);
  }
}

TEST(InMemory, ABadCurveIsRefusedAsItsFileIs) {
  Points3 few(4, 3), doubled(6, 3), crossing(8, 3);
  few << 0, 0, 0, 10, 0, 0, 10, 10, 0, 0, 10, 5;
  doubled << 0, 0, 0, 10, 0, 0, 10, 0, 0, 10, 10, 0, 5, 12, 3, 0, 10, 5;
  // A figure eight in the plane z = 0: it crosses itself at the origin.
  for (int i = 0; i < 8; ++i) {
    const double t = 2 * M_PI * i / 8;
    crossing.row(i) << 20 * std::sin(t), 10 * std::sin(2 * t), 0;
  }
  InverseSettings settings;
  settings.resolution = 40;
  CurveReadOptions closed;
  closed.forceClosed = true;
  for (const Points3& points : {Points3(0, 3), few, doubled, crossing}) {
    std::string text = "[";
    char number[96];
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      std::snprintf(number, sizeof number, "%s[%.17g, %.17g, %.17g]", i ? ", " : "", points(i, 0),
                    points(i, 1), points(i, 2));
      text += number;
    }
    text += "]";
    SCOPED_TRACE(text);
    MessageSink sink;
    const Result<InverseRun> made = makePieces(Curve3{points, "curve.json", ""}, settings, sink);
    const Result<Curve3> read = parseCurve(text, "curve.json", closed);
    ASSERT_FALSE(read.isOk());
    ASSERT_FALSE(made.isOk());
    EXPECT_EQ(made.status().code(), read.status().code());
    EXPECT_EQ(made.status().message(), read.status().message());
  }
}

}  // namespace
}  // namespace dform
