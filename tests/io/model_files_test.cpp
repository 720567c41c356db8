// SPDX-License-Identifier: GPL-3.0-or-later
// Result models on disk: exact write/read round trip and consistency checks on reading.
#include "dform/io/model_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

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
    piece.shape.row(i) << 90 * std::cos(t) * (1 + jitter(rng) * 1e-7), 60 * std::sin(t),
        1e-300 * jitter(rng);
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

/// A polar-grid annulus: rings + 1 circles of `sectors` vertices from radius 20 to 50 mm, vertex
/// ring * sectors + s. Its hole is the seam (clockwise), its outer loop a free boundary
/// (counter-clockwise: the piece on its left), with two radial creases from the hole to the
/// outline.
Piece makeAnnulus(const std::string& name, int sectors, int rings, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  auto id = [&](int ring, int s) { return ring * sectors + (s % sectors); };
  Piece piece;
  piece.name = name;
  piece.flat.resize((rings + 1) * sectors, 2);
  piece.shape.resize(piece.flat.rows(), 3);
  for (int ring = 0; ring <= rings; ++ring)
    for (int s = 0; s < sectors; ++s) {
      const double t = 2 * M_PI * s / sectors, rho = 20 + 30.0 * ring / rings;
      piece.flat.row(id(ring, s)) << rho * std::cos(t) + jitter(rng) * 1e-3, rho * std::sin(t);
      piece.shape.row(id(ring, s)) << rho * std::cos(t), rho * std::sin(t),
          7.25 * ring + jitter(rng) / 3;
    }
  piece.F.resize(2 * rings * sectors, 3);
  for (int ring = 0, f = 0; ring < rings; ++ring)
    for (int s = 0; s < sectors; ++s) {
      piece.F.row(f++) << id(ring, s), id(ring + 1, s), id(ring + 1, s + 1);
      piece.F.row(f++) << id(ring, s), id(ring + 1, s + 1), id(ring, s + 1);
    }
  for (int s = sectors; s > 0; --s) piece.seam.push_back(id(0, s));
  piece.freeBoundaries.emplace_back();
  for (int s = 0; s < sectors; ++s) piece.freeBoundaries[0].push_back(id(rings, s));
  for (int s : {0, sectors / 2}) {
    piece.creases.emplace_back();
    for (int ring = 0; ring <= rings; ++ring) piece.creases.back().push_back(id(ring, s));
  }
  return piece;
}

DForm makeVariant() {
  std::mt19937 rng(11);
  return {makeAnnulus("A", 16, 3, rng), makeAnnulus("B", 16, 3, rng)};
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

std::string file(const test::ScratchDir& dir, const char* name) {
  return (std::filesystem::path(dir.path()) / name).string();
}

// Writes `model`, reads it back and expects every field as written.
void expectExactRoundTrip(const DForm& model) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  const Result<DForm> back = readModel(dir.path());
  ASSERT_TRUE(back.isOk()) << back.status().message();
  for (const auto& [written, read] :
       {std::make_pair(&model.a, &back.value().a), std::make_pair(&model.b, &back.value().b)}) {
    EXPECT_EQ(read->name, written->name);
    EXPECT_EQ(read->flat, written->flat);  // bit-exact: shortest round-trip decimals
    EXPECT_EQ(read->shape, written->shape);
    EXPECT_EQ(read->F, written->F);
    EXPECT_EQ(read->seam, written->seam);
    EXPECT_EQ(read->freeBoundaries, written->freeBoundaries);
    EXPECT_EQ(read->creases, written->creases);
  }
}

TEST(ModelFiles, RoundTripIsExact) { expectExactRoundTrip(makeModel()); }

TEST(ModelFiles, FileLayout) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  const std::string flat = readText(file(dir, ModelFileNames::aFlat));
  EXPECT_EQ(flat.rfind("# dform", 0), 0u);
  EXPECT_NE(flat.find(" 0\nv "), std::string::npos);       // flat vertices have z = 0
  EXPECT_NE(flat.find("\nf 1 2 3\n"), std::string::npos);  // 1-based faces
  EXPECT_NE(flat.find("\nl 2 3 4 5 6 7 8 9 10 11 12 13\n"),
            std::string::npos);  // first index not repeated
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
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
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputUnreadable,
                        file(dir, ModelFileNames::b3d)));
}

TEST(ModelFiles, DifferentFacesInFlatAnd3d) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::a3d), "\nf 1 2 3\n", "\nf 1 3 2\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::a3d), "different faces"));
}

TEST(ModelFiles, DifferentSeamInFlatAnd3d) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::b3d), "\nl 2 ", "\nl 3 ");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::b3d), "different seam"));
}

TEST(ModelFiles, SeamCountsOfPiecesDiffer) {
  test::ScratchDir dir;
  std::mt19937 rng(3);
  const DForm model{makePiece("A", 12, rng, false), makePiece("B", 10, rng, true)};
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::bFlat),
                        "seam has 10 vertices but piece A's has 12"));
}

TEST(ModelFiles, IndexOutOfRange) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::aFlat), "\nf 1 2 3\n", "\nf 1 2 99\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputUnreadable,
                        file(dir, ModelFileNames::aFlat), "out of range"));
}

TEST(ModelFiles, FlatFileMustBeFlat) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::string text = readText(file(dir, ModelFileNames::bFlat));
  const auto firstVertexEnd = text.find(" 0\n", text.find("\nv "));
  text.replace(firstVertexEnd, 3, " 2.5\n");
  std::ofstream(file(dir, ModelFileNames::bFlat), std::ios::trunc) << text;
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::bFlat), "not flat"));
}

TEST(ModelFiles, SeamPolylineMissingOrDoubled) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::a3d), "\nl ", "\n# l ");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::a3d), "0 seam polylines"));
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::ofstream(file(dir, ModelFileNames::a3d), std::ios::app) << "l 1 2 3\n";
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::a3d), "2 seam polylines"));
}

TEST(ModelFiles, QuadFaceRejected) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  replaceInFile(file(dir, ModelFileNames::aFlat), "\nf 1 2 3\n", "\nf 1 2 3 4\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::aFlat), "expected a triangle"));
}

TEST(ModelFiles, DifferentVertexCount) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  std::ofstream(file(dir, ModelFileNames::b3d), std::ios::app) << "v 1 2 3\n";
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::b3d), "number of vertices"));
}

TEST(ModelFiles, VariantRoundTripIsExact) {
  const DForm model = makeVariant();
  ASSERT_FALSE(model.a.freeBoundaries.empty());
  ASSERT_EQ(model.b.creases.size(), 2u);
  expectExactRoundTrip(model);
}

TEST(ModelFiles, EveryPolylineIsInItsGroup) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeVariant()).isOk());
  for (const char* name : {ModelFileNames::aFlat, ModelFileNames::b3d}) {
    const std::string text = readText(file(dir, name));
    EXPECT_NE(text.find("\ng seam\nl 1 16 15 "), std::string::npos)
        << name;  // the hole, first index once
    EXPECT_NE(text.find("\ng boundary\nl 49 50 51 "), std::string::npos) << name;
    EXPECT_NE(text.find("\ng crease\nl 1 17 33 49\nl 9 25 41 57\n"), std::string::npos) << name;
  }
  // A classic model has a seam group only.
  ASSERT_TRUE(writeModel(dir.path(), makeModel()).isOk());
  const std::string classic = readText(file(dir, ModelFileNames::aFlat));
  EXPECT_NE(classic.find("\ng seam\nl 2 3 4 "), std::string::npos);
  EXPECT_EQ(classic.find("g boundary"), std::string::npos);
  EXPECT_EQ(classic.find("g crease"), std::string::npos);
}

TEST(ModelFiles, OldFileWithOneUngroupedPolylineReadsAsTheSeam) {
  test::ScratchDir dir;
  const DForm model = makeModel();
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  for (const char* name :
       {ModelFileNames::aFlat, ModelFileNames::a3d, ModelFileNames::bFlat, ModelFileNames::b3d})
    replaceInFile(file(dir, name), "\ng seam\n", "\n");
  ASSERT_EQ(readText(file(dir, ModelFileNames::aFlat)).find("\ng "), std::string::npos);
  const Result<DForm> back = readModel(dir.path());
  ASSERT_TRUE(back.isOk()) << back.status().message();
  EXPECT_EQ(back.value().a.seam, model.a.seam);
  EXPECT_EQ(back.value().b.seam, model.b.seam);
  EXPECT_TRUE(back.value().a.freeBoundaries.empty());
  EXPECT_TRUE(back.value().a.creases.empty());
}

TEST(ModelFiles, FlatAnd3dMustAgreeOnBoundariesAndCreases) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeVariant()).isOk());
  replaceInFile(file(dir, ModelFileNames::a3d), "\nl 9 25 41 57\n", "\nl 10 26 42 58\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::a3d), "different creases"));
  ASSERT_TRUE(writeModel(dir.path(), makeVariant()).isOk());
  replaceInFile(file(dir, ModelFileNames::b3d), "\ng crease\n", "\ng boundary\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::b3d), "different free boundaries"));
}

// Writes `model` after `spoil` changed piece A, and expects readModel to fail on A's flat file.
void expectBadPieceA(const std::function<void(Piece&)>& spoil, ErrorCode code,
                     const std::string& part) {
  test::ScratchDir dir;
  DForm model = makeVariant();
  spoil(model.a);
  ASSERT_TRUE(writeModel(dir.path(), model).isOk());
  EXPECT_TRUE(
      failsWith(readModel(dir.path()).status(), code, file(dir, ModelFileNames::aFlat), part));
}

TEST(ModelFiles, BadCreasesAreRejected) {
  // A jump across the annulus: vertices 1 (hole) and 50 (outline) share no edge.
  expectBadPieceA(
      [](Piece& p) {
        p.creases[1] = {0, 49};
      },
      ErrorCode::InputInvalid, "crease 2 is not along mesh edges: vertices 1 and 50 share no edge");
  // Along the outline: a boundary edge, not a fold.
  expectBadPieceA(
      [](Piece& p) {
        p.creases[0] = {48, 49, 50};
      },
      ErrorCode::InputInvalid, "crease 1 runs along the boundary");
  // Stopping in the middle of the piece.
  expectBadPieceA([](Piece& p) { p.creases[0].pop_back(); }, ErrorCode::InputInvalid,
                  "crease 1 ends at vertex 33, which is not on the boundary");
  // An index past the last vertex is a malformed OBJ statement, as for faces and the seam.
  expectBadPieceA([](Piece& p) { p.creases[0].back() = 999; }, ErrorCode::InputUnreadable,
                  "vertex index 1000 is out of range");
}

TEST(ModelFiles, BadFreeBoundariesAreRejected) {
  expectBadPieceA(
      [](Piece& p) {
        p.freeBoundaries[0] = {16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31};
      },
      ErrorCode::InputInvalid, "free boundary 1 is not a boundary");
  expectBadPieceA(
      [](Piece& p) { std::reverse(p.freeBoundaries[0].begin(), p.freeBoundaries[0].end()); },
      ErrorCode::InputInvalid, "free boundary 1 runs the wrong way");
  expectBadPieceA(
      [](Piece& p) {
        p.freeBoundaries[0] = {48, 49, 51};
      },
      ErrorCode::InputInvalid, "free boundary 1 is not along mesh edges");
  expectBadPieceA(
      [](Piece& p) {
        p.freeBoundaries[0] = {48, 49};
      },
      ErrorCode::InputInvalid, "free boundary 1 has fewer than 3 vertices");
}

TEST(ModelFiles, PolylineInAnUnknownGroupIsRejected) {
  test::ScratchDir dir;
  ASSERT_TRUE(writeModel(dir.path(), makeVariant()).isOk());
  replaceInFile(file(dir, ModelFileNames::bFlat), "\ng crease\n", "\ng folds\n");
  EXPECT_TRUE(failsWith(readModel(dir.path()).status(), ErrorCode::InputInvalid,
                        file(dir, ModelFileNames::bFlat), "a polyline in group 'folds'"));
}

}  // namespace
}  // namespace dform
