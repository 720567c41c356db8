// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/validate/gate.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <set>

#include "models.h"
#include "pipeline/reference_seams.h"

namespace dform {
namespace {

using Names = std::set<std::string>;
using Verdict = CheckResult::Verdict;

Names withVerdict(const GateReport& report, Verdict verdict) {
  Names names;
  for (const CheckResult& c : report.checks)
    if (c.verdict == verdict) names.insert(c.name);
  return names;
}
Names failed(const GateReport& report) { return withVerdict(report, Verdict::Fail); }
Names notRun(const GateReport& report) { return withVerdict(report, Verdict::NotRun); }

std::string describe(const GateReport& report) {
  std::string text;
  for (const CheckResult& c : report.checks)
    text += c.name + " " + verdictName(c.verdict) + " " + std::to_string(c.value) + " (" +
            c.detail + ")\n";
  return text;
}

const Names kForwardChecks = {"L_error",           "L_max",
                              "B_error",           "seam_gap_mm",
                              "gauss_max_rad",     "flipped",
                              "degenerate",        "flat_simple",
                              "seam_length_rel",   "self_intersection",
                              "hull_distance_rel", "exact_distance_rel"};

TEST(Gate, AVertexOnTheSeamHullMeasuresZeroEveryRun) {
  // The tetrahedral D-Form's faces are the hull's facets, many seam points to each, which CGAL
  // triangulates in an address-dependent order: on the hull is 0, not ~1e-13 of the diagonal that
  // changed from run to run (and made a run's gate differ from the same gate measured again).
  DForm model = test::tetraDForm(8);
  const CheckResult onHull =
      *measureAndGate(model, GateLimits{}, nullptr).find("hull_distance_rel");
  EXPECT_EQ(onHull.value, 0.0) << onHull.detail;
  EXPECT_NE(onHull.detail.find("at piece A vertex 0;"), std::string::npos) << onHull.detail;
  // The floor hides nothing larger: a vertex off the seam moved 1e-9 of the diagonal inwards
  // is measured.
  std::vector<bool> onSeam(std::size_t(model.a.shape.rows()), false);
  for (int v : model.a.seam) onSeam[std::size_t(v)] = true;
  const int inner = int(std::find(onSeam.begin(), onSeam.end(), false) - onSeam.begin());
  ASSERT_LT(inner, model.a.shape.rows());
  const double diagonal = 2.0 * std::sqrt(2.0) * 40.0;  // the seam's bounding box: 80 x 80 x 20 mm
  model.a.shape.row(inner) *= 1.0 - 1e-9 * diagonal / model.a.shape.row(inner).norm();
  const CheckResult inside =
      *measureAndGate(model, GateLimits{}, nullptr).find("hull_distance_rel");
  EXPECT_GT(inside.value, 1e-10) << inside.detail;
  EXPECT_LT(inside.value, 2e-9) << inside.detail;
}

TEST(Gate, ExactConvexDFormPassesEveryCheck) {
  const GateReport report = measureAndGate(test::tetraDForm(8), GateLimits{}, nullptr);
  Names names;
  for (const CheckResult& c : report.checks) names.insert(c.name);
  EXPECT_EQ(names, kForwardChecks);
  EXPECT_EQ(report.checks.size(), kForwardChecks.size());
  EXPECT_EQ(withVerdict(report, Verdict::Pass), kForwardChecks) << describe(report);
  EXPECT_TRUE(report.passed());
  EXPECT_LT(report.find("hull_distance_rel")->value, 1e-12);  // the surface is its seam's hull
  // ... and the exact engine, which knows only the flat pieces, makes that very shape.
  EXPECT_LT(report.find("exact_distance_rel")->value, 1e-9);
  EXPECT_LT(report.metrics.exactDistanceMaxRel, 1e-9);
}

TEST(Gate, StretchedShapeFailsLErrorAndTheExactDistance) {
  DForm model = test::tetraDForm(8);
  model.a.shape *= 1.01;
  model.b.shape *= 1.01;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  // 1% on every edge: L_error (limit 0.5%) fails; L_max (limit 3%) holds; angles, seam, hull and
  // flat pieces are unchanged by a uniform scaling, but the shape is 1% larger than the one the
  // cut pieces make: its seam lies ~0.5% of the diagonal off it (limit 0.2%).
  EXPECT_EQ(failed(report), (Names{"L_error", "exact_distance_rel"})) << describe(report);
  EXPECT_TRUE(notRun(report).empty()) << describe(report);
  EXPECT_NEAR(report.find("L_error")->value, 0.01, 1e-12);
  EXPECT_FALSE(report.passed());
}

// NaN is no figure: a check whose value is NaN fails (never passes by a comparison that NaN
// slips through), and so does the gate.
TEST(Gate, NaNFailsEveryCheckItReachesAndTheGate) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(judgeCheck("x", nan, 1.0, "").verdict, Verdict::Fail);
  EXPECT_EQ(judgeCheck("x", 0.5, nan, "").verdict, Verdict::Fail);
  EXPECT_EQ(judgeCheck("x", 0.5, 1.0, "").verdict, Verdict::Pass);
  DForm model = test::tetraDForm(8);
  model.a.shape(0, 0) = nan;  // one coordinate of a corner of the seam
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  for (const CheckResult& c : report.checks) {
    if (std::isnan(c.value)) {
      EXPECT_NE(c.verdict, Verdict::Pass) << describe(report);
    }
  }
  EXPECT_TRUE(failed(report).count("L_error")) << describe(report);
  EXPECT_TRUE(failed(report).count("L_max")) << describe(report);
  // The checks on exact predicates fail without reaching CGAL, which asserts on a NaN.
  for (const char* name : {"self_intersection", "hull_distance_rel"}) {
    EXPECT_EQ(report.find(name)->verdict, Verdict::Fail) << describe(report);
    EXPECT_NE(report.find(name)->detail.find("piece A's 3D vertex 0"), std::string::npos);
  }
  EXPECT_FALSE(report.passed());
  DForm flatNaN = test::tetraDForm(8);
  flatNaN.b.flat(3, 1) = std::numeric_limits<double>::infinity();
  const GateReport flatReport = measureAndGate(flatNaN, GateLimits{}, nullptr);
  EXPECT_NE(flatReport.find("self_intersection")->detail.find("piece B's flat vertex 3"),
            std::string::npos)
      << describe(flatReport);
  EXPECT_FALSE(flatReport.passed());
}

TEST(Gate, FlatPieceOverlappingItselfFailsOnlyFlatSimple) {
  // 1.2 turns of a gently rising ribbon: the flat pieces wrap past 360 degrees and overlap, the 3D
  // ribbon clears itself by 2*pi*1.5 mm a turn.
  const DForm model = test::ribbonDForm(test::Ribbon{});
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  EXPECT_EQ(failed(report), Names{"flat_simple"}) << describe(report);
  EXPECT_NE(report.find("flat_simple")->detail.find("piece A: outline edges"), std::string::npos);
  // No vertex is away from the seam and the pieces are not convex: said so, not passed.
  EXPECT_EQ(notRun(report), (Names{"exact_distance_rel", "gauss_max_rad", "hull_distance_rel"}));
  EXPECT_FALSE(report.find("hull_distance_rel")->detail.empty());
  EXPECT_FALSE(report.find("exact_distance_rel")->detail.empty());
  EXPECT_TRUE(std::isnan(report.find("gauss_max_rad")->value));
}

TEST(Gate, OverlappingFlatTrianglesInsideASimpleOutlineFailFlatSimple) {
  DForm model = test::tetraDForm(8);
  // Drag one interior flat vertex across two of its neighbours: its triangles flip and overlap
  // the others while the outline stays simple.
  Eigen::Index v;
  (model.a.flat.rowwise() - model.a.flat.colwise().mean()).rowwise().squaredNorm().minCoeff(&v);
  int f = 0;
  while (model.a.F(f, 0) != v) ++f;
  model.a.flat.row(v) += 2.5 * (model.a.flat.row(model.a.F(f, 1)) - model.a.flat.row(v));
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const CheckResult* simple = report.find("flat_simple");
  EXPECT_EQ(simple->verdict, Verdict::Fail) << describe(report);
  EXPECT_NE(simple->detail.find("overlapping triangle pairs"), std::string::npos) << simple->detail;
  EXPECT_EQ(simple->detail.find("outline"), std::string::npos) << simple->detail;
  EXPECT_EQ(report.find("flipped")->verdict, Verdict::Fail);
}

TEST(Gate, OpenSeamFailsOnlyBErrorAndSeamGap) {
  DForm model = test::tetraDForm(8);
  model.b.shape.col(2).array() += 1.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  EXPECT_EQ(failed(report), (Names{"B_error", "seam_gap_mm"})) << describe(report);
  EXPECT_NEAR(report.find("seam_gap_mm")->value, 1.0, 1e-12);
}

TEST(Gate, SelfIntersectingShapeFailsOnlySelfIntersection) {
  // A steep ribbon (a cone-like band: its flat pieces span about 190 degrees, no overlap) whose
  // outer edge rises while its inner edge falls: the second turn cuts through the first.
  test::Ribbon ribbon;
  ribbon.innerLift = 20.0;
  ribbon.outerRise = 1.0;
  ribbon.innerRise = -1.0;
  const GateReport report = measureAndGate(test::ribbonDForm(ribbon), GateLimits{}, nullptr);
  EXPECT_EQ(failed(report), Names{"self_intersection"}) << describe(report);
  EXPECT_GT(report.find("self_intersection")->value, 0.0);
}

TEST(Gate, VertexPushedThroughTheOtherPieceFailsTheHonestSet) {
  DForm model = test::tetraDForm(8);
  // Push A's vertex nearest the middle of hinge AC straight up through piece B (the top faces
  // are at most 20 mm above it): its edges stretch, its ring folds over, and the spike
  // pierces B.
  Eigen::Index v;
  model.a.shape.rowwise().squaredNorm().minCoeff(&v);
  model.a.shape(v, 2) += 30.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  EXPECT_EQ(failed(report), (Names{"L_error", "L_max", "gauss_max_rad", "flipped",
                                   "self_intersection", "hull_distance_rel"}))
      << describe(report);
}

TEST(Gate, InverseModeChecksDErrorInsteadOfBError) {
  DForm model = test::tetraDForm(8);
  Curve3 target;
  target.points.resize(Eigen::Index(model.a.seam.size()), 3);
  for (size_t i = 0; i < model.a.seam.size(); ++i)
    target.points.row(Eigen::Index(i)) = model.a.shape.row(model.a.seam[i]);
  const GateReport exact = measureAndGate(model, GateLimits{}, &target);
  EXPECT_EQ(exact.find("B_error"), nullptr);
  ASSERT_NE(exact.find("D_error"), nullptr);
  EXPECT_TRUE(exact.passed()) << describe(exact);
  ASSERT_TRUE(exact.curve.has_value());

  target.points.col(0).array() += 1.0;  // the curve moved 1 mm away from both sides
  const GateReport shifted = measureAndGate(model, GateLimits{}, &target);
  EXPECT_EQ(failed(shifted), Names{"D_error"}) << describe(shifted);
  EXPECT_NEAR(shifted.curve->curveDistanceMaxMm, 1.0, 1e-12);

  target.points.conservativeResize(target.points.rows() - 1, 3);
  const GateReport mismatched = measureAndGate(model, GateLimits{}, &target);
  EXPECT_EQ(mismatched.find("D_error")->verdict, Verdict::NotRun);
  EXPECT_NE(mismatched.find("D_error")->detail.find("seam pairs"), std::string::npos);
}

TEST(Gate, HullDistanceOfAVertexPushedOutOfTheHull) {
  DForm model = test::tetraDForm(8);
  // Piece A's face A-D-C lies on a hull face; push one of its interior vertices out along the
  // face's outward normal: its distance to the hull is exactly the push.
  const Eigen::Vector3d A(-40, 0, -10), D(0, 40, 10), C(40, 0, -10);
  const Eigen::Vector3d normal = (D - A).cross(C - A).normalized();
  const Eigen::Vector3d inside = (A + D + C) / 3.0;
  Eigen::Index v;
  (model.a.shape.rowwise() - inside.transpose()).rowwise().squaredNorm().minCoeff(&v);
  const double push = 1.5;
  model.a.shape.row(v) += push * normal.transpose();
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const double diagonal = Eigen::Vector3d(80, 80, 20).norm();  // the seam's bounding box
  EXPECT_NEAR(report.find("hull_distance_rel")->value, push / diagonal, 1e-12) << describe(report);
  EXPECT_EQ(report.find("hull_distance_rel")->verdict, Verdict::Fail);  // 1.2% > 1%
}

TEST(Gate, HullDistanceOfAVertexDeepInsideIsItsNearestFacesPlane) {
  // Off the centre, the four faces of the tetrahedral D-Form's hull lie at four distances; a
  // vertex moved there measures the smallest, to the plane of the nearest face.
  DForm model = test::tetraDForm(8);
  const Eigen::Vector3d A(-40, 0, -10), B(0, -40, 10), C(40, 0, -10), D(0, 40, 10);
  const Eigen::Vector3d p(6, -3, 2);
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
  for (const auto& [a, b, c] :
       {std::array{A, B, C}, std::array{A, C, D}, std::array{A, B, D}, std::array{B, C, D}}) {
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    nearest = std::min(nearest, std::abs(normal.dot(p - a)));
    farthest = std::max(farthest, std::abs(normal.dot(p - a)));
  }
  ASSERT_GT(farthest - nearest, 1.0);  // the four planes are told apart
  std::vector<bool> onSeam(std::size_t(model.a.shape.rows()), false);
  for (int v : model.a.seam) onSeam[std::size_t(v)] = true;
  const int inner = int(std::find(onSeam.begin(), onSeam.end(), false) - onSeam.begin());
  model.a.shape.row(inner) = p.transpose();
  const double diagonal = Eigen::Vector3d(80, 80, 20).norm();
  const CheckResult hull = *measureAndGate(model, GateLimits{}, nullptr).find("hull_distance_rel");
  EXPECT_NEAR(hull.value, nearest / diagonal, 1e-12) << hull.detail;
  EXPECT_NE(hull.detail.find("at piece A vertex " + std::to_string(inner) + ";"), std::string::npos)
      << hull.detail;
}

TEST(Gate, ConvexityIsJudgedWithinWhatSamplingAndSolvingMayMove) {
  // The solve may leave a seam corner up to 3e-4 of the perimeter L from where it was drawn, so a
  // convex outline may come back with a pocket up to 2 * 3e-4 * L deep (the disphenoid's straight
  // sides add no chord-loss move). Push the middle vertex of A's first flat side inward.
  const DForm exact = test::tetraDForm(8);
  const Piece& a = exact.a;
  const Eigen::Vector2d p0 = a.flat.row(a.seam[0]), p1 = a.flat.row(a.seam[8]);
  const Eigen::Vector2d inward = Eigen::Vector2d(-(p1 - p0).y(), (p1 - p0).x()).normalized();
  double perimeter = 0.0;
  for (size_t i = 0; i < a.seam.size(); ++i)
    perimeter += (a.flat.row(a.seam[i]) - a.flat.row(a.seam[(i + 1) % a.seam.size()])).norm();
  const double tolerance = 2 * 3e-4 * perimeter;
  auto pushed = [&](double depth) {
    DForm model = exact;
    model.a.flat.row(model.a.seam[4]) += depth * inward.transpose();
    return *measureAndGate(model, GateLimits{}, nullptr).find("hull_distance_rel");
  };
  // A pocket of a millionth of a millimetre turns the wrong way by far more than sin = 1e-9, yet
  // is sampling noise: judged convex, the check runs.
  for (const double depth : {1e-6, 0.9 * tolerance}) {
    const CheckResult shallow = pushed(depth);
    EXPECT_NE(shallow.verdict, Verdict::NotRun) << depth << ": " << shallow.detail;
  }
  const CheckResult deep = pushed(1.1 * tolerance);
  EXPECT_EQ(deep.verdict, Verdict::NotRun);
  EXPECT_NE(deep.detail.find("piece A is not convex: its flat seam has a pocket"),
            std::string::npos)
      << deep.detail;
}

TEST(Gate, FlatDoubleDiscTouchesItselfAndPasses) {
  // Both pieces lie in z = 0 on top of each other: a doubly covered disc, a flat pouch zipped at
  // its rim. Its sheets touch face to face without crossing (a buildable object); its planar seam
  // has no hull.
  const GateReport report =
      measureAndGate(test::flatDoubleDisc(4, 24, 50.0), GateLimits{}, nullptr);
  EXPECT_TRUE(failed(report).empty()) << describe(report);
  EXPECT_EQ(report.find("self_intersection")->value, 0.0);
  EXPECT_NE(report.find("self_intersection")->detail.find("face to face"), std::string::npos)
      << report.find("self_intersection")->detail;
  EXPECT_EQ(report.find("hull_distance_rel")->verdict, Verdict::NotRun);
  EXPECT_NE(report.find("hull_distance_rel")->detail.find("planar"), std::string::npos);
}

// The flat double disc with the vertices of B (the lower sheet: its faces point down) off the
// seam lifted by lift(x, y) mm.
DForm liftedLowerSheet(const std::function<double(double, double)>& lift) {
  DForm model = test::flatDoubleDisc(4, 24, 50.0);
  std::vector<bool> onSeam(size_t(model.b.shape.rows()), false);
  for (int v : model.b.seam) onSeam[size_t(v)] = true;
  for (Eigen::Index v = 0; v < model.b.shape.rows(); ++v)
    if (!onSeam[size_t(v)]) model.b.shape(v, 2) += lift(model.b.shape(v, 0), model.b.shape(v, 1));
  return model;
}

TEST(Gate, LowerSheetOfAFlatPouchPushedThroughTheUpperOneIntersects) {
  // B's centre pushed up by a micrometre: its middle triangles tilt up through A.
  const auto centre = [](double height) {
    return [height](double x, double y) { return x == 0.0 && y == 0.0 ? height : 0.0; };
  };
  const CheckResult through = *measureAndGate(liftedLowerSheet(centre(1e-3)), GateLimits{}, nullptr)
                                   .find("self_intersection");
  EXPECT_EQ(through.verdict, Verdict::Fail) << through.detail;
  EXPECT_GT(through.value, 0.0);
  // Moved by a thousandth of the tolerance (1e-9 of the 141 mm diagonal) the sheets still touch.
  const CheckResult touching =
      *measureAndGate(liftedLowerSheet(centre(1e-12 * 141.0)), GateLimits{}, nullptr)
           .find("self_intersection");
  EXPECT_EQ(touching.verdict, Verdict::Pass) << touching.detail;
  // Bulging away from A (downwards) the pouch opens: no contact, no crossing.
  const CheckResult open = *measureAndGate(liftedLowerSheet([](double x, double y) {
                                             return -5.0 * (1.0 - (x * x + y * y) / 2500.0);
                                           }),
                                           GateLimits{}, nullptr)
                                .find("self_intersection");
  EXPECT_EQ(open.value, 0.0) << open.detail;
  EXPECT_EQ(open.detail.find("face to face"), std::string::npos) << open.detail;
}

TEST(Gate, FlatPouchTouchesWhicheverWayItsFacesAreWound) {
  // B's faces listed the other way round (as a file may hold them): the check orients the closed
  // surface by its seam before comparing which way the sheets face.
  DForm model = test::flatDoubleDisc(4, 24, 50.0);
  model.b.F.col(1).swap(model.b.F.col(2));
  const CheckResult check = *measureAndGate(model, GateLimits{}, nullptr).find("self_intersection");
  EXPECT_EQ(check.verdict, Verdict::Pass) << check.detail;
}

TEST(Gate, ExactCreasedDFormPassesWithItsHingesFoldedSharply) {
  // The hinges fold by 117 degrees: a fold-over without creases, a drawn fold with them.
  const GateReport plain = measureAndGate(test::tetraDForm(8, 40.0, 0.7), GateLimits{}, nullptr);
  EXPECT_EQ(plain.find("flipped")->verdict, Verdict::Fail);
  const GateReport report =
      measureAndGate(test::creasedTetraDForm(8, 40.0, 0.7), GateLimits{}, nullptr);
  EXPECT_TRUE(failed(report).empty()) << describe(report);
  EXPECT_EQ(notRun(report), Names{"hull_distance_rel"}) << describe(report);
  EXPECT_NE(report.find("hull_distance_rel")->detail.find("creases"), std::string::npos);
  EXPECT_NE(report.find("gauss_max_rad")->detail.find("creases"), std::string::npos);
}

TEST(Gate, AntiDFormPassesAndHullIsNotRun) {
  const GateReport report = measureAndGate(test::annulusDForm(), GateLimits{}, nullptr);
  EXPECT_TRUE(failed(report).empty()) << describe(report);
  EXPECT_EQ(notRun(report), (Names{"exact_distance_rel", "hull_distance_rel"})) << describe(report);
  EXPECT_NE(report.find("hull_distance_rel")->detail.find("free boundary"), std::string::npos);
  EXPECT_NE(report.find("exact_distance_rel")->detail.find("hole"), std::string::npos);
  EXPECT_NE(report.find("flat_simple")->detail.find("holes inside"), std::string::npos);
  EXPECT_EQ(report.find("self_intersection")->value, 0.0);
  EXPECT_LT(report.find("seam_gap_mm")->value, 1e-12);
}

TEST(Gate, HoleMeetingTheOutlineFailsFlatSimple) {
  DForm model = test::annulusDForm();
  // Drag a hole vertex of A out across the outer outline (radius 20 -> 60).
  const int v = model.a.seam[5];
  model.a.flat.row(v) *= 3.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const CheckResult* simple = report.find("flat_simple");
  EXPECT_EQ(simple->verdict, Verdict::Fail) << describe(report);
  EXPECT_NE(simple->detail.find("piece A: seam loop edge"), std::string::npos) << simple->detail;
  EXPECT_NE(simple->detail.find("free boundary 1 edge"), std::string::npos) << simple->detail;
}

TEST(Gate, LoopsOutsideTheOutlineOrInsideAHoleFailFlatSimple) {
  DForm model = test::annulusDForm();
  Piece& a = model.a;
  // Two small triangles of unused vertices listed as free boundaries: one beyond the outer
  // outline (R = 50), one inside the hole (r = 20).
  const Eigen::Index n = a.flat.rows();
  a.flat.conservativeResize(n + 6, 2);
  a.shape.conservativeResize(n + 6, 3);
  a.flat.bottomRows(6) << 80, 0, 82, 0, 80, 2, 0, 0, 2, 0, 0, 2;
  a.shape.bottomRows(6).setZero();
  a.freeBoundaries.push_back({int(n), int(n) + 1, int(n) + 2});
  a.freeBoundaries.push_back({int(n) + 3, int(n) + 4, int(n) + 5});
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const CheckResult* simple = report.find("flat_simple");
  EXPECT_EQ(simple->verdict, Verdict::Fail);
  EXPECT_NE(simple->detail.find("free boundary 2 lies outside the outer outline"),
            std::string::npos)
      << simple->detail;
  EXPECT_NE(simple->detail.find("free boundary 3 lies inside seam loop"), std::string::npos)
      << simple->detail;
  EXPECT_EQ(simple->detail.find("free boundary 1 lies"), std::string::npos) << simple->detail;
}

TEST(Gate, AntiDFormPiercingItselfFailsSelfIntersection) {
  DForm model = test::annulusDForm();
  // B hangs below z = 0 and A rises above it; lift an interior vertex of B through A.
  Eigen::Index v = 0;
  (model.b.flat.rowwise().norm().array() - 35.0).abs().minCoeff(&v);
  model.b.shape(v, 2) = 10.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  EXPECT_EQ(report.find("self_intersection")->verdict, Verdict::Fail) << describe(report);
}

}  // namespace
}  // namespace dform
