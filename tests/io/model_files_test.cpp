// Result models on disk: exact write/read round trip and consistency checks on reading.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/model_files.h"
#include "test_util.h"

namespace dform {
namespace {

using test::failsWith;

/// A small fan-triangulated polygon with awkward coordinates (full-precision doubles).
Piece makePiece(const std::string& name, int n, std::mt19937& rng, bool clockwiseSeam) {
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  Piece piece;
  piece.name = name;
  piece.flat.resize(n + 1, 2);
  piece.shape.resize(n + 1, 3);
  piece.flat.row(0) << jitter(rng) * 1e-3, jitter(rng) * 1e-3;
  piece.shape.row(0) << 0.1 * jitter(rng), 0.2 * jitter(rng), 123.456789 + jitter(rng);
  for (int i = 1; i <= n; ++i) {
    const double t = 2 * M_PI * (i - 1) / n;
    piece.flat.row(i) << 100 * std::cos(t) + jitter(rng) / 3, 70 * std::sin(t) + jitter(rng) / 7;
    piece.shape.row(i) << 90 * std::cos(t) * (1 + jitter(rng) * 1e-7), 60 * std::sin(t), 1e-300 * jitter(rng);
  }
  piece.F.resize(n, 3);
  for (int i = 0; i < n; ++i) piece.F.row(i) << 0, 1 + i, 1 + (i + 1) % n;
  for (int i = 0; i < n; ++i) piece.seam.push_back(clockwiseSeam ? 1 + (n - i) % n : 1 + i);
  return piece;
}

DForm makeModel() {
  std::mt19937 rng(7);
  return {makePiece("A", 12, rng, false), makePiece("B", 12, rng, true)};
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void replaceInFile(const std::string& path, const std::string& from, const std::string& to) {
  std::string text = readText(path);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(path, std::ios::trunc) << text;
}

std::string file(const test::ScratchDir& dir, const char* name) { return (std::filesystem::path(dir.path()) / name).string(); }

TEST(ModelFiles, RoundTripIsExact) {
  test::ScratchDir dir;
  const DForm model = makeModel();
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  const Result<DForm> back = readModel(dir.path());
  ASSERT_TRUE(back.isOk()) << back.status().message();
  for (const auto& [written, read] : {std::make_pair(&model.a, &back.value().a), std::make_pair(&model.b, &back.value().b)}) {
    EXPECT_EQ(read->name, written->name);
    EXPECT_EQ(read->flat, written->flat);  // bit-exact: shortest round-trip decimals
    EXPECT_EQ(read->shape, written->shape);
    EXPECT_EQ(read->F, written->F);
    EXPECT_EQ(read->seam, written->seam);
  }
}

TEST(ModelFiles, FileLayout) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  const std::string flat = readText(file(dir, ModelFileNames::aFlat));
  EXPECT_EQ(flat.rfind("# dform", 0), 0u);
  EXPECT_NE(flat.find(" 0\nv "), std::string::npos);  // flat vertices have z = 0
  EXPECT_NE(flat.find("\nf 1 2 3\n"), std::string::npos);  // 1-based faces
  EXPECT_NE(flat.find("\nl 2 3 4 5 6 7 8 9 10 11 12 13\n"), std::string::npos);  // first index not repeated
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 4);  // no temporaries left behind
}

TEST(ModelFiles, MissingFolderIsAnOutputError) {
  test::ScratchDir dir;
  const std::string missing = dir.path() + "/not-there";
  const Status status = writeModel(missing, makeModel());
  EXPECT_EQ(status.code(), ErrorCode::OutputFailed);
  EXPECT_NE(status.message().find(missing), std::string::npos);
}

TEST(ModelFiles, MissingFileOnRead) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::filesystem::remove(file(dir, ModelFileNames::b3d));
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputUnreadable, file(dir, ModelFileNames::b3d)));
}

TEST(ModelFiles, DifferentFacesInFlatAnd3d) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::a3d), "\nf 1 2 3\n", "\nf 1 3 2\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::a3d), "different faces"));
}

TEST(ModelFiles, DifferentSeamInFlatAnd3d) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::b3d), "\nl 2 ", "\nl 3 ");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::b3d), "different seam"));
}

TEST(ModelFiles, SeamCountsOfPiecesDiffer) {
  test::ScratchDir dir;
  std::mt19937 rng(3);
  const DForm model{makePiece("A", 12, rng, false), makePiece("B", 10, rng, true)};
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::bFlat),
                        "seam has 10 vertices but piece A's has 12"));
}

TEST(ModelFiles, IndexOutOfRange) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::aFlat), "\nf 1 2 3\n", "\nf 1 2 99\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputUnreadable, file(dir, ModelFileNames::aFlat), "out of range"));
}

TEST(ModelFiles, FlatFileMustBeFlat) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::string text = readText(file(dir, ModelFileNames::bFlat));
  const auto firstVertexEnd = text.find(" 0\n", text.find("\nv "));
  text.replace(firstVertexEnd, 3, " 2.5\n");
  std::ofstream(file(dir, ModelFileNames::bFlat), std::ios::trunc) << text;
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::bFlat), "not flat"));
}

TEST(ModelFiles, SeamPolylineMissingOrDoubled) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::a3d), "\nl ", "\n# l ");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::a3d), "0 seam polylines"));
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::ofstream(file(dir, ModelFileNames::a3d), std::ios::app) << "l 1 2 3\n";
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::a3d), "2 seam polylines"));
}

TEST(ModelFiles, QuadFaceRejected) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::aFlat), "\nf 1 2 3\n", "\nf 1 2 3 4\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::aFlat), "expected a triangle"));
}

TEST(ModelFiles, DifferentVertexCount) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::ofstream(file(dir, ModelFileNames::b3d), std::ios::app) << "v 1 2 3\n";
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid, file(dir, ModelFileNames::b3d), "number of vertices"));
}

}  // namespace
}  // namespace dform
