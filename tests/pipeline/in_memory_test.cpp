// The in-memory entries (makeDForm, makePieces): shapes and curves that never were files give the
// same D-Form as the files that hold them, and their messages name the pieces without a path.
#include <gtest/gtest.h>

#include <cmath>

#include "io/curve_reader.h"
#include "io/outline_reader.h"
#include "pipeline/forward_pipeline.h"
#include "pipeline/inverse_pipeline.h"

namespace dform {
namespace {

std::string sample(const std::string& name) { return std::string(DFORM_SAMPLES_DIR) + "/" + name; }

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
  job.pieceA = sample("forward/ellipses-a.svg");
  job.pieceB = sample("forward/ellipses-b.svg");
  job.resolution = 60;
  MessageSink fileSink, memorySink;
  const Result<ForwardRun> fromFiles = runForward(job, fileSink);
  Result<Shape2> a = readShape(job.pieceA), b = readShape(job.pieceB);
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
}

TEST(InMemory, ACurveGivesThePiecesItsFileGives) {
  InverseJob job;
  job.curve = sample("inverse/tennis-ball.obj");
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

}  // namespace
}  // namespace dform
