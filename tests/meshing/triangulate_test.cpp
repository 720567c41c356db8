// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/meshing/triangulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"

namespace dform {
namespace {

// A closed outline sampled densely from a polar or parametric function, then resampled uniformly.
template <typename Curve>
Points2 sampleCurve(Curve curve, int dense = 4000) {
  Points2 P(dense, 2);
  for (int i = 0; i < dense; ++i) P.row(i) = curve(2.0 * kPi * i / dense);
  return P;
}

Points2 polygon(std::initializer_list<std::pair<double, double>> corners) {
  Points2 P(Eigen::Index(corners.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [x, y] : corners) P.row(i++) << x, y;
  return P;
}

// Uniform resampling with edge length as close to h as a whole count allows.
Points2 resampleTo(const Points2& P, double h) {
  const int n = std::max(3, int(std::lround(closedLength(P) / h)));
  return resampleClosed(P, n);
}

Points2 circle(double r, double cx = 0.0, double cy = 0.0) {
  return sampleCurve(
      [&](double t) { return Eigen::RowVector2d(cx + r * std::cos(t), cy + r * std::sin(t)); });
}

double minAngleDegrees(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& c) {
  auto angle = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const Eigen::Vector2d u = q - p, v = r - p;
    return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v)) * 180.0 / kPi;
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

struct MeshStats {
  double minAngleAll = 180.0;       // every triangle
  double minAngleInterior = 180.0;  // triangles with no outline or hole vertex
  double meanInteriorEdge = 0.0;    // edges that are not outline or hole edges
};

// Every property triangulateDomain promises, checked on one result.
MeshStats checkMesh(const FlatMesh& mesh, const Points2& boundary,
                    const std::vector<Points2>& holes) {
  MeshStats stats;
  const Eigen::Index B = boundary.rows();
  // Fixed points: bit-identical and in order, outline then holes.
  std::vector<std::pair<int, int>> loopEdges;
  int first = 0;
  auto addLoop = [&](const Points2& loop) {
    EXPECT_TRUE(mesh.V.middleRows(first, loop.rows()) == loop) << "loop points moved or reordered";
    for (int k = 0; k < loop.rows(); ++k)
      loopEdges.emplace_back(first + k, first + int((k + 1) % loop.rows()));
    first += int(loop.rows());
  };
  addLoop(boundary);
  for (const Points2& hole : holes) addLoop(hole);
  const int fixedCount = first;
  EXPECT_EQ(mesh.boundary.size(), std::size_t(B));
  for (Eigen::Index i = 0; i < B && i < Eigen::Index(mesh.boundary.size()); ++i)
    EXPECT_EQ(mesh.boundary[std::size_t(i)], int(i));

  // Triangles: counter-clockwise, inside the domain, covering exactly its area.
  double area = 0.0;
  std::vector<int> uses(std::size_t(mesh.V.rows()), 0);
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
    const Eigen::Vector2d a = mesh.V.row(mesh.F(t, 0)), b = mesh.V.row(mesh.F(t, 1)),
                          c = mesh.V.row(mesh.F(t, 2));
    const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    EXPECT_GT(twice, 0.0) << "triangle " << t << " is not counter-clockwise";
    area += 0.5 * twice;
    const Eigen::Vector2d centroid = (a + b + c) / 3.0;
    EXPECT_TRUE(insidePolygon(boundary, centroid)) << "triangle " << t << " outside the outline";
    for (const Points2& hole : holes)
      EXPECT_FALSE(insidePolygon(hole, centroid)) << "triangle " << t << " inside a hole";
    const double angle = minAngleDegrees(a, b, c);
    stats.minAngleAll = std::min(stats.minAngleAll, angle);
    if (mesh.F.row(t).minCoeff() >= fixedCount)
      stats.minAngleInterior = std::min(stats.minAngleInterior, angle);
    for (int k = 0; k < 3; ++k) {
      ++uses[std::size_t(mesh.F(t, k))];
      ++directed[{mesh.F(t, k), mesh.F(t, (k + 1) % 3)}];
    }
  }
  double expectedArea = signedArea(boundary);
  for (const Points2& hole : holes) expectedArea -= std::abs(signedArea(hole));
  EXPECT_NEAR(area, expectedArea, 1e-9 * expectedArea);
  for (std::size_t v = 0; v < uses.size(); ++v)
    EXPECT_GT(uses[v], 0) << "vertex " << v << " unused";

  // Manifold: loop edges in exactly one triangle (so none was split), every other edge in two
  // with opposite directions; Euler characteristic 1 for a disc, 0 for an annulus.
  std::set<std::pair<int, int>> loopSet;
  for (const auto& [a, b] : loopEdges) {
    loopSet.insert({std::min(a, b), std::max(a, b)});
    EXPECT_EQ(directed.count({a, b}) + directed.count({b, a}), 1u)
        << "loop edge " << a << "-" << b << " is not a single triangle edge";
  }
  std::size_t edges = 0, interiorEdges = 0;
  double interiorLength = 0.0;
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "-" << e.second << " repeated";
    const std::pair<int, int> key{std::min(e.first, e.second), std::max(e.first, e.second)};
    const bool twin = directed.count({e.second, e.first}) > 0;
    if (twin && e.first > e.second) continue;  // count each undirected edge once
    ++edges;
    if (loopSet.count(key)) {
      EXPECT_FALSE(twin) << "loop edge " << key.first << "-" << key.second << " in two triangles";
    } else {
      EXPECT_TRUE(twin) << "inner edge " << key.first << "-" << key.second << " on the border";
      ++interiorEdges;
      interiorLength += (mesh.V.row(key.first) - mesh.V.row(key.second)).norm();
    }
  }
  const long euler = long(mesh.V.rows()) - long(edges) + long(mesh.F.rows());
  EXPECT_EQ(euler, holes.empty() ? 1 : 1 - long(holes.size()));
  stats.meanInteriorEdge = interiorEdges ? interiorLength / double(interiorEdges) : 0.0;
  return stats;
}

struct Case {
  std::string name;
  Points2 boundary;
  std::vector<Points2> holes;
  double h;
};

// Meshes, checks every invariant and the quality aims, and prints the statistics.
FlatMesh meshAndCheck(const Case& c, bool checkQuality = true) {
  TriangulateOptions options;
  options.targetEdgeLength = c.h;
  const auto start = std::chrono::steady_clock::now();
  Result<FlatMesh> result = triangulateDomain(c.boundary, c.holes, options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(result.isOk()) << c.name << ": " << result.status().message();
  if (!result.isOk()) return {};
  const FlatMesh& mesh = result.value();
  SCOPED_TRACE(c.name);
  const MeshStats stats = checkMesh(mesh, c.boundary, c.holes);
  std::printf(
      "  %-14s V=%5d F=%5d boundary=%4d  min angle %5.1f (all) %5.1f (interior)  "
      "mean edge/h %.3f  %.2f ms\n",
      c.name.c_str(), int(mesh.V.rows()), int(mesh.F.rows()), int(c.boundary.rows()),
      stats.minAngleAll, stats.minAngleInterior, stats.meanInteriorEdge / c.h, ms);
  if (checkQuality) {
    EXPECT_GE(stats.minAngleInterior, options.minAngleDegrees - 5.0);
    EXPECT_NEAR(stats.meanInteriorEdge / c.h, 1.0, 0.25);
  }
  return mesh;
}

Points2 lShape() { return polygon({{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}}); }

Points2 star() {
  return sampleCurve([](double t) {
    const double r = 8.0 + 3.0 * std::cos(5.0 * t);
    return Eigen::RowVector2d(r * std::cos(t), r * std::sin(t));
  });
}

TEST(TriangulateDomain, StandardShapesKeepTheirBoundaryAndMeetTheAims) {
  const double h = 0.5;
  const std::vector<Case> cases = {
      {"circle", resampleTo(circle(10.0), h), {}, h},
      {"ellipse",
       resampleTo(sampleCurve([](double t) {
                    return Eigen::RowVector2d(12.0 * std::cos(t), 6.0 * std::sin(t));
                  }),
                  h),
       {},
       h},
      {"square", resampleTo(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), h), {}, h},
      {"star", resampleTo(star(), h), {}, h},
      {"kidney",
       resampleTo(sampleCurve([](double t) {
                    const double r = 8.0 + 2.5 * std::cos(t) - 1.5 * std::cos(2.0 * t);
                    return Eigen::RowVector2d(r * std::cos(t), 0.8 * r * std::sin(t));
                  }),
                  h),
       {},
       h},
      {"L-shape", resampleTo(lShape(), h), {}, h},
      {"thin 20:1", resampleTo(polygon({{0, 0}, {20, 0}, {20, 1}, {0, 1}}), 0.1), {}, 0.1},
      {"annulus", resampleTo(circle(10.0), h), {resampleTo(circle(4.0), h)}, h},
  };
  std::printf("\n");
  for (const Case& c : cases) meshAndCheck(c);
}

TEST(TriangulateDomain, HoleOrientationDoesNotMatter) {
  const double h = 0.5;
  const Points2 hole = resampleTo(circle(3.0, 2.0, -1.0), h);
  const Points2 clockwiseHole = hole.colwise().reverse();
  meshAndCheck({"hole ccw", resampleTo(circle(10.0), h), {hole}, h});
  meshAndCheck({"hole cw", resampleTo(circle(10.0), h), {clockwiseHole}, h});
  meshAndCheck({"two holes",
                resampleTo(circle(10.0), h),
                {resampleTo(circle(2.5, -4.0, 0.0), h), resampleTo(circle(2.5, 4.0, 0.0), h)},
                h});
}

// Sharp reflex corners, spikes and a channel narrower than h: the boundary must survive anyway.
// Triangle quality near such features is whatever the boundary allows, so only the invariants
// are asserted here; the statistics are printed.
TEST(TriangulateDomain, SharpCornersAndThinPartsNeverSplitTheBoundary) {
  const double h = 0.5;
  const std::vector<Case> cases = {
      {"comb",
       resampleTo(polygon({{0, 0},
                           {12, 0},
                           {12, 8},
                           {11.1, 8},
                           {11, 1},
                           {10.9, 8},
                           {6.1, 8},
                           {6, 1},
                           {5.9, 8},
                           {0, 8}}),
                  h),
       {},
       h},
      {"dumbbell",
       resampleTo(polygon({{0, 0},
                           {6, 0},
                           {6, 2.8},
                           {14, 2.8},
                           {14, 0},
                           {20, 0},
                           {20, 6},
                           {14, 6},
                           {14, 3.1},
                           {6, 3.1},
                           {6, 6},
                           {0, 6}}),
                  h),
       {},
       h},
      {"sliver 1:200", resampleTo(polygon({{0, 0}, {20, 0}, {20, 0.1}, {0, 0.1}}), h), {}, h},
      {"spiky star",
       resampleTo(sampleCurve([](double t) {
                    const double r = 6.0 + 5.0 * std::pow(std::cos(4.0 * t), 8);
                    return Eigen::RowVector2d(r * std::cos(t), r * std::sin(t));
                  }),
                  h),
       {},
       h},
      {"raw L", lShape(), {}, 2.0},  // corners only: few, long boundary edges
  };
  std::printf("\n");
  for (const Case& c : cases) meshAndCheck(c, false);
}

// Jagged random star-shaped outlines, with and without a hole, and target lengths from a fifth
// to three times the boundary spacing: the invariants hold for every one of them.
TEST(TriangulateDomain, RandomJaggedOutlinesKeepTheirBoundary) {
  std::mt19937 random(2024);
  std::uniform_real_distribution<double> radius(2.0, 8.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int corners = 5 + int(unit(random) * 40);
    Points2 raw(corners, 2);
    for (int i = 0; i < corners; ++i) {
      const double t = 2.0 * kPi * (i + 0.4 * unit(random)) / corners, r = radius(random);
      raw.row(i) << r * std::cos(t), r * std::sin(t);
    }
    const double spacing = 0.2 + 0.5 * unit(random);
    const Points2 outline = trial % 4 == 3 ? raw : resampleTo(raw, spacing);
    std::vector<Points2> holes;
    if (trial % 2 == 1) holes.push_back(resampleTo(circle(1.0), spacing));
    TriangulateOptions options;
    options.targetEdgeLength = spacing * (0.2 + 2.8 * unit(random));
    const Result<FlatMesh> mesh = triangulateDomain(outline, holes, options);
    ASSERT_TRUE(mesh.isOk()) << "trial " << trial << ": " << mesh.status().message();
    SCOPED_TRACE("trial " + std::to_string(trial));
    checkMesh(mesh.value(), outline, holes);
  }
}

TEST(TriangulateDomain, DifferentOutlinesWithTheSameCountKeepItOneToOne) {
  const int n = 160;
  const Points2 a = resampleClosed(circle(10.0), n);
  const Points2 b = resampleClosed(lShape(), n);
  TriangulateOptions optionsA, optionsB;
  optionsA.targetEdgeLength = closedLength(a) / n;
  optionsB.targetEdgeLength = closedLength(b) / n;
  const Result<FlatMesh> meshA = triangulateDomain(a, {}, optionsA);
  const Result<FlatMesh> meshB = triangulateDomain(b, {}, optionsB);
  ASSERT_TRUE(meshA.isOk() && meshB.isOk());
  EXPECT_EQ(meshA.value().boundary.size(), std::size_t(n));
  EXPECT_EQ(meshB.value().boundary.size(), std::size_t(n));
  checkMesh(meshA.value(), a, {});
  checkMesh(meshB.value(), b, {});
}

TEST(TriangulateDomain, IsDeterministic) {
  const Points2 outline = resampleTo(star(), 0.5);
  TriangulateOptions options;
  options.targetEdgeLength = 0.5;
  const Result<FlatMesh> first = triangulateDomain(outline, {}, options);
  const Result<FlatMesh> second = triangulateDomain(outline, {}, options);
  ASSERT_TRUE(first.isOk() && second.isOk());
  EXPECT_TRUE(first.value().V == second.value().V);
  EXPECT_TRUE(first.value().F == second.value().F);
}

TEST(TriangulateDomain, PieceOfAbout500VerticesTiming) {
  // The size the solver typically gets; the time is printed, never asserted.
  const Points2 outline = resampleClosed(circle(10.0), 80);
  TriangulateOptions options;
  options.targetEdgeLength = closedLength(outline) / 80;
  const auto start = std::chrono::steady_clock::now();
  const int runs = 20;
  Result<FlatMesh> mesh = triangulateDomain(outline, {}, options);
  for (int r = 1; r < runs; ++r) mesh = triangulateDomain(outline, {}, options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(mesh.isOk());
  std::printf("  %d vertices, %d triangles: %.2f ms per mesh\n", int(mesh.value().V.rows()),
              int(mesh.value().F.rows()), ms / runs);
  checkMesh(mesh.value(), outline, {});
}

void expectInvalid(const Points2& boundary, const std::vector<Points2>& holes, ErrorCode code,
                   const std::string& words, double h = 0.5) {
  TriangulateOptions options;
  options.targetEdgeLength = h;
  const Result<FlatMesh> result = triangulateDomain(boundary, holes, options);
  ASSERT_FALSE(result.isOk()) << words;
  EXPECT_EQ(result.status().code(), code) << result.status().message();
  EXPECT_NE(result.status().message().find(words), std::string::npos) << result.status().message();
  EXPECT_EQ(result.status().message().find('\n'), std::string::npos);
}

TEST(TriangulateDomain, RejectsBadInput) {
  const Points2 square = resampleTo(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), 0.5);
  expectInvalid(square.colwise().reverse(), {}, ErrorCode::InputInvalid, "clockwise");
  expectInvalid(polygon({{0, 0}, {1, 0}}), {}, ErrorCode::InputInvalid, "fewer than 3");
  expectInvalid(polygon({{0, 0}, {10, 10}, {10, 0}, {0, 10}}), {}, ErrorCode::InputInvalid,
                "crosses itself");
  expectInvalid(polygon({{0, 0}, {1, 0}, {1, 0}, {0, 1}}), {}, ErrorCode::InputInvalid, "repeats");
  expectInvalid(polygon({{0, 0}, {1, 0}, {NAN, 1}}), {}, ErrorCode::InputInvalid, "non-finite");
  expectInvalid(polygon({{0, 0}, {1, 0}, {2, 0}}), {}, ErrorCode::InputInvalid, "no area");
  expectInvalid(square, {resampleTo(circle(2.0, 20.0, 5.0), 0.5)}, ErrorCode::InputInvalid,
                "hole 0 is not wholly inside the outline");
  expectInvalid(square, {resampleTo(circle(2.0, 9.0, 5.0), 0.5)}, ErrorCode::InputInvalid,
                "hole 0 is not wholly inside the outline");  // crossing, first point outside
  expectInvalid(square, {resampleTo(circle(2.0, 1.0, 5.0), 0.5)}, ErrorCode::InputInvalid,
                "cross or touch");  // crossing, first point inside
  expectInvalid(square,
                {resampleTo(circle(3.0, 5.0, 5.0), 0.5), resampleTo(circle(1.0, 5.0, 5.0), 0.5)},
                ErrorCode::InputInvalid, "hole 1 overlaps hole 0");
  expectInvalid(square,
                {resampleTo(circle(2.0, 4.0, 5.0), 0.5), resampleTo(circle(2.0, 6.0, 5.0), 0.5)},
                ErrorCode::InputInvalid, "hole 0 overlaps hole 1");
  expectInvalid(square,
                {resampleTo(circle(1.0, 4.0, 5.0), 0.5), resampleTo(circle(1.0, 4.0, 6.9), 0.5)},
                ErrorCode::InputInvalid, "cross or touch");  // crossing, first points outside
  // A hole touching the outline at one of its points.
  expectInvalid(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), {polygon({{5, 0}, {6, 2}, {4, 2}})},
                ErrorCode::InputInvalid, "cross or touch");
  expectInvalid(square, {}, ErrorCode::Usage, "edge length", 0.0);
  expectInvalid(square, {}, ErrorCode::Usage, "edge length", NAN);
  expectInvalid(square, {}, ErrorCode::InputInvalid, "too small", 1e-5);
}

// A 10 x 10 square with 80 boundary points (row 20k is corner k) and creases between the given
// boundary rows, each with interior points every h along it.
struct CreasedSquare {
  Points2 outline = resampleTo(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), 0.5);
  std::vector<InteriorLine> lines;
  void addCrease(int from, int to, double h = 0.5) {
    Points2 ends(2, 2);
    ends << outline.row(from), outline.row(to);
    const int segments = std::max(1, int(std::lround((ends.row(1) - ends.row(0)).norm() / h)));
    const Eigen::MatrixXd points = resampleOpen(ends, segments);
    lines.push_back({from, to, points.middleRows(1, segments - 1)});
  }
};

TEST(TriangulateDomain, CreaseLinesAreMeshEdgesWithTrianglesOnBothSides) {
  CreasedSquare c;
  c.addCrease(0, 40);         // the diagonal, 27 points along it
  c.addCrease(40, 70);        // (10, 10) to (0, 5): shares a corner with the diagonal
  c.addCrease(10, 30, 10.0);  // a single edge cutting off the corner (10, 0)
  TriangulateOptions options;
  options.targetEdgeLength = 0.5;
  const Result<FlatMesh> result = triangulateDomain(c.outline, {}, options, c.lines);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const FlatMesh& mesh = result.value();
  checkMesh(mesh, c.outline, {});  // creases change neither the domain nor its topology
  ASSERT_EQ(mesh.lines.size(), c.lines.size());
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{mesh.F(t, k), mesh.F(t, (k + 1) % 3)}];
  int next = int(c.outline.rows());  // interior crease points follow the outline, in order
  for (std::size_t k = 0; k < c.lines.size(); ++k) {
    const std::vector<int>& line = mesh.lines[k];
    ASSERT_EQ(line.size(), std::size_t(c.lines[k].interior.rows()) + 2);
    EXPECT_EQ(line.front(), c.lines[k].from);
    EXPECT_EQ(line.back(), c.lines[k].to);
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      EXPECT_EQ(line[i], next++);
      EXPECT_TRUE(Eigen::RowVector2d(mesh.V.row(line[i])) ==
                  c.lines[k].interior.row(Eigen::Index(i) - 1));
    }
    for (std::size_t i = 0; i + 1 < line.size(); ++i)  // a triangle on each side of every edge
      EXPECT_TRUE(directed.count({line[i], line[i + 1]}) && directed.count({line[i + 1], line[i]}))
          << "crease " << k << " edge " << i;
  }
}

TEST(TriangulateDomain, RejectsCreasesThatDoNotStayInside) {
  TriangulateOptions options;
  options.targetEdgeLength = 0.5;
  auto expectBad = [&](const Points2& outline, const std::vector<Points2>& holes,
                       const InteriorLine& line, const std::string& words) {
    const Result<FlatMesh> result = triangulateDomain(outline, holes, options, {line});
    ASSERT_FALSE(result.isOk()) << words;
    EXPECT_EQ(result.status().code(), ErrorCode::InputInvalid);
    EXPECT_NE(result.status().message().find(words), std::string::npos)
        << result.status().message();
  };
  CreasedSquare c;
  c.addCrease(10, 50);  // (5, 0) to (5, 10) across the hole below
  expectBad(c.outline, {resampleTo(circle(1.5, 5.0, 5.0), 0.5)}, c.lines[0],
            "crease lines cross or touch");
  expectBad(c.outline, {}, {0, 80, {}}, "does not join two boundary points");
  expectBad(c.outline, {}, {3, 3, {}}, "does not join two boundary points");
  // In the L shape the chord from (10, 4) to (4, 10) runs outside it, touching it at its ends only.
  expectBad(lShape(), {}, {2, 4, {}}, "leaves the piece");
}

}  // namespace
}  // namespace dform
