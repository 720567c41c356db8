// SPDX-License-Identifier: GPL-3.0-or-later
// Edge strain (the L per edge the studio draws) and where the gate's failing checks fail.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"
#include "models.h"
#include "pipeline/reference_seams.h"
#include "validate/mesh_measures.h"

namespace dform {
namespace {

using Edge = std::pair<int, int>;

// Each undirected edge of the faces once, from the faces themselves.
std::set<Edge> faceEdges(const Faces& F) {
  std::set<Edge> out;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.insert(std::minmax(F(f, k), F(f, (k + 1) % 3)));
  return out;
}

const FailureSites* sitesOf(const std::vector<FailureSites>& all, const std::string& check) {
  for (const FailureSites& s : all)
    if (s.check == check) return &s;
  return nullptr;
}

std::set<Edge> edgePairs(const std::vector<int>& items) {
  std::set<Edge> out;
  for (size_t k = 0; k + 1 < items.size(); k += 2) out.insert({items[k], items[k + 1]});
  return out;
}

TEST(EdgeStrain, EveryEdgeOnceSignedAndItsLargestIsLMax) {
  DForm model = test::tetraDForm(6);
  const int v = model.a.F(7, 0);
  model.a.shape.row(v) *= 1.2;  // one vertex pushed outward: its edges stretch or shrink
  const std::vector<EdgeStrain> strains = edgeStrains(model.a);
  std::set<Edge> seen;
  double largest = 0;
  for (const EdgeStrain& e : strains) {
    EXPECT_LT(e.from, e.to);
    seen.insert({e.from, e.to});
    const double L = (model.a.flat.row(e.from) - model.a.flat.row(e.to)).norm();
    const double Lh = (model.a.shape.row(e.from) - model.a.shape.row(e.to)).norm();
    EXPECT_NEAR(e.strain, (Lh - L) / L, 1e-15);
    if (e.from != v && e.to != v) {
      EXPECT_NEAR(e.strain, 0, 1e-12);
    }
    largest = std::max(largest, std::abs(e.strain));
  }
  EXPECT_EQ(seen, faceEdges(model.a.F));
  EXPECT_EQ(seen.size(), strains.size());
  for (const EdgeStrain& e : edgeStrains(model.b)) largest = std::max(largest, std::abs(e.strain));
  EXPECT_GT(largest, 0.05);
  EXPECT_EQ(largest, computeMetrics(model, {}).lengthErrorMax);

  model.a.shape *= 2;  // every edge twice as long as flat: +1; half as long: -0.5
  for (const EdgeStrain& e : edgeStrains(model.a)) {
    if (e.from != v && e.to != v) {
      EXPECT_NEAR(e.strain, 1.0, 1e-12);
    }
  }
  model.b.shape *= 0.5;
  for (const EdgeStrain& e : edgeStrains(model.b)) EXPECT_NEAR(e.strain, -0.5, 1e-12);
}

TEST(FailureSites, APassingShapeHasNone) {
  const DForm model = test::tetraDForm(6);
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  ASSERT_TRUE(report.passed());
  EXPECT_TRUE(locateFailures(model, report).empty());
}

TEST(FailureSites, StrainedEdgesAreTheEdgesOverTheLimit) {
  DForm model = test::tetraDForm(6);
  const int v = model.a.F(7, 0);
  model.a.shape.row(v) *= 1.2;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  ASSERT_EQ(report.find("L_max")->verdict, CheckResult::Verdict::Fail);
  const std::vector<FailureSites> all = locateFailures(model, report);
  const FailureSites* lmax = sitesOf(all, "L_max");
  ASSERT_NE(lmax, nullptr);
  EXPECT_EQ(lmax->kind, FailureSites::Kind::Edges);
  std::set<Edge> over;
  for (const EdgeStrain& e : edgeStrains(model.a))
    if (std::abs(e.strain) > GateLimits{}.lengthErrorMax) over.insert({e.from, e.to});
  EXPECT_FALSE(over.empty());
  EXPECT_EQ(edgePairs(lmax->items[0]), over);
  for (const Edge& e : over) EXPECT_TRUE(e.first == v || e.second == v);
  EXPECT_TRUE(lmax->items[1].empty());  // B is untouched
  // Checks that fail without sites here are named by none.
  for (const FailureSites& s : all)
    EXPECT_TRUE(s.check == "L_max" || s.check == "L_error" || s.check == "gauss_max_rad" ||
                s.check == "seam_gap_mm")
        << s.check;
}

TEST(FailureSites, UniformStretchMarksEveryEdgeForLErrorOnly) {
  DForm model = test::tetraDForm(4);
  model.a.shape *= 1.01;
  model.b.shape *= 1.01;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const std::vector<FailureSites> all = locateFailures(model, report);
  ASSERT_NE(sitesOf(all, "L_error"), nullptr);
  EXPECT_EQ(sitesOf(all, "L_max"), nullptr);  // 1 % is under L_max's 3 %
  EXPECT_EQ(edgePairs(sitesOf(all, "L_error")->items[0]), faceEdges(model.a.F));
  EXPECT_EQ(edgePairs(sitesOf(all, "L_error")->items[1]), faceEdges(model.b.F));
}

TEST(FailureSites, OpenSeamMarksEverySeamPointFartherThanTheLimit) {
  DForm model = test::tetraDForm(8);
  const int n = int(model.b.seam.size());
  for (int k = 0; k < n / 2; ++k) model.b.shape(model.b.seam[size_t(k)], 2) += 1.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  const std::vector<FailureSites> all = locateFailures(model, report);
  const FailureSites* gaps = sitesOf(all, "seam_gap_mm");
  ASSERT_NE(gaps, nullptr);
  std::vector<int> expected;
  for (int k = 0; k < n / 2; ++k) expected.push_back(k);
  EXPECT_EQ(gaps->kind, FailureSites::Kind::SeamPoints);
  EXPECT_EQ(gaps->items[0], expected);
  EXPECT_EQ(gaps->items[1], expected);
}

TEST(FailureSites, CurvedVerticesAreTheCheckedVerticesOverTheLimit) {
  DForm model = test::flatDoubleDisc(5, 24, 50.0);
  // An interior vertex away from the seam lifted: a cone there and around it.
  const std::vector<bool> away = detail::awayFromSeam(model.a, detail::edgeTopology(model.a.F));
  int v = 0;
  while (!away[size_t(v)]) ++v;
  model.a.shape(v, 2) += 3.0;
  const GateReport report = measureAndGate(model, GateLimits{}, nullptr);
  ASSERT_EQ(report.find("gauss_max_rad")->verdict, CheckResult::Verdict::Fail);
  const std::vector<FailureSites> all = locateFailures(model, report);
  const FailureSites* curved = sitesOf(all, "gauss_max_rad");
  ASSERT_NE(curved, nullptr);
  const Eigen::VectorXd defect = detail::angleDefects(model.a.shape, model.a.F);
  std::vector<int> expected;
  for (int u = 0; u < int(defect.size()); ++u)
    if (away[size_t(u)] && std::abs(defect(u)) > GateLimits{}.gaussMaxRad) expected.push_back(u);
  EXPECT_EQ(curved->items[0], expected);
  EXPECT_NE(std::find(expected.begin(), expected.end(), v), expected.end());
  EXPECT_TRUE(curved->items[1].empty());
}

}  // namespace
}  // namespace dform
