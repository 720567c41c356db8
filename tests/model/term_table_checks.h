// SPDX-License-Identifier: GPL-3.0-or-later
// Checks that hold for every table of terms and weights (model/term_table.h): the forward tests
// run them on forwardTerms, the inverse tests on inverseTerms.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <set>
#include <vector>

#include "dform/model/term_table.h"
#include "test_meshes.h"

namespace dform::test {

/// The weights struct holds nothing but the table's weights, and each row names a member of its
/// own: one distinct value per row, written through the rows, is found once in the struct's bytes.
template <typename Weights>
void expectEveryWeightOnce(const TermTable<Weights>& table) {
  ASSERT_EQ(sizeof(Weights), table.size() * sizeof(double)) << "a weight without its row";
  Weights weights;
  for (std::size_t k = 0; k < table.size(); ++k) weights.*table[k].weight = double(k + 1);
  std::vector<double> stored(table.size());
  std::memcpy(stored.data(), &weights, sizeof(Weights));
  std::sort(stored.begin(), stored.end());
  for (std::size_t k = 0; k < table.size(); ++k)
    EXPECT_EQ(stored[k], double(k + 1)) << "two rows share a member";
  std::set<std::string> names;
  for (const TermRow<Weights>& row : table) EXPECT_TRUE(names.insert(row.name).second) << row.name;
}

/// Two small meshed pieces with a shared seam, every drawn (seam) vertex anchored: what a solve
/// builds its terms from.
struct TermFixture {
  Piece a = meshedPiece(ellipse(1.2, 0.8), 16, false);
  Piece b = meshedPiece(ellipse(1.0, 0.97), 16, true);
  VariableLayout layout{int(a.flat.rows()), int(b.flat.rows()), a.seam, b.seam};
  EdgeLengthPairs edges = meshEdgePairs(layout, a.F, b.F);
  TermInputs inputs() const { return {layout, a, b, edges, a.seam, b.seam}; }
};

/// A row is marked linear exactly when its factory makes a LinearResidual (the relaxation takes
/// those as they are); a row without a factory is not linear.
template <typename Weights>
void expectLinearFlagsMatchTheTerms(const TermTable<Weights>& table) {
  const TermFixture fixture;
  for (const TermRow<Weights>& row : table) {
    if (!row.make) {
      EXPECT_FALSE(row.linear) << row.name << " makes no term";
      continue;
    }
    const std::unique_ptr<ResidualTerm> term = row.make(fixture.inputs());
    ASSERT_TRUE(term) << row.name;
    EXPECT_GT(term->numResiduals(), 0) << row.name;
    EXPECT_EQ(dynamic_cast<const LinearResidual*>(term.get()) != nullptr, row.linear) << row.name;
  }
}

/// A Problem built from the table holds each row's term under its name and weight, in the table's
/// order, and the relaxation's list is the linear rows' terms with their weights.
template <typename Weights>
void expectProblemFollowsTheTable(const TermTable<Weights>& table) {
  const TermFixture fixture;
  Weights weights;
  for (std::size_t k = 0; k < table.size(); ++k) weights.*table[k].weight = 0.5 + double(k);
  std::vector<std::unique_ptr<ResidualTerm>> terms = makeTerms(table, fixture.inputs());
  const auto linear = linearTerms(table, terms, weights);
  Problem problem(fixture.layout.numVariables());
  addTerms(problem, table, terms, weights);
  int t = 0;
  std::size_t l = 0;
  for (const TermRow<Weights>& row : table) {
    if (!row.make) continue;
    ASSERT_LT(t, problem.numTerms()) << row.name;
    EXPECT_EQ(problem.termName(t), row.name);
    EXPECT_EQ(problem.termWeight(t), weights.*row.weight) << row.name;
    if (row.linear) {
      ASSERT_LT(l, linear.size()) << row.name;
      EXPECT_EQ(linear[l].first, weights.*row.weight) << row.name;
      EXPECT_EQ(linear[l].second, &problem.term(t)) << row.name;
      ++l;
    }
    ++t;
  }
  EXPECT_EQ(t, problem.numTerms());
  EXPECT_EQ(l, linear.size());
}

/// All of the above on one table: the forward and the inverse tests run it on theirs.
template <typename Weights>
void expectTermTableHolds(const TermTable<Weights>& table) {
  {
    SCOPED_TRACE("every weight has one row");
    expectEveryWeightOnce(table);
  }
  {
    SCOPED_TRACE("linear flags");
    expectLinearFlagsMatchTheTerms(table);
  }
  SCOPED_TRACE("the Problem and the relaxation's list");
  expectProblemFollowsTheTable(table);
}

}  // namespace dform::test
