// SPDX-License-Identifier: GPL-3.0-or-later
// relaxThenSolve: the relaxation, then Levenberg-Marquardt or the relaxation's multiplier rounds,
// as forward and inverse modelling both run it.
#include "dform/model/relax_then_solve.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "dform/model/term_table.h"
#include "term_table_checks.h"

namespace dform {
namespace {

// The forward objective on two small pieces (term_table_checks.h's fixture), every seam vertex
// anchored by the boundary-fix term, from a start lifted off the plane and shaken: a problem
// whose relaxation and solve both have work to do.
struct SolveFixture {
  test::TermFixture pieces;
  ForwardWeights weights;
  std::vector<std::unique_ptr<ResidualTerm>> terms = makeTerms(forwardTerms(), pieces.inputs());
  LinearResidual* anchors = static_cast<LinearResidual*>(
      terms[rowOf(forwardTerms(), &ForwardWeights::boundaryFix)].get());
  Eigen::VectorXd x0 = start();
  std::unique_ptr<LocalGlobalRelaxation> relaxation;
  Problem problem{pieces.layout.numVariables()};
  FoldGuard guard{pieces.layout, pieces.a, pieces.b};

  SolveFixture() {
    weightByFlatLength(pieces.edges, x0, weights.isometry);
    relaxation = std::make_unique<LocalGlobalRelaxation>(
        linearTerms(forwardTerms(), terms, weights), pieces.edges, x0);
    addTerms(problem, forwardTerms(), terms, weights);
    problem.setBlockSize(VariableLayout::kPerVertex);
  }

  Eigen::VectorXd start() const {
    Piece a = pieces.a, b = pieces.b;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> shake(-0.05, 0.05);
    for (Piece* p : {&a, &b}) {
      p->shape = Points3::Zero(p->flat.rows(), 3);
      for (Eigen::Index i = 0; i < p->flat.rows(); ++i)
        p->shape.row(i) << p->flat(i, 0) + shake(random), p->flat(i, 1) + shake(random),
            (p == &a ? 0.2 : -0.2) + shake(random);
    }
    return packVariables(pieces.layout, a, b);
  }

  // The relaxation alone from x0, as relaxThenSolve runs it first.
  Eigen::VectorXd relaxedAlone(const LocalGlobalOptions& options) const {
    Eigen::VectorXd x = x0;
    relaxation->relax(options, x);
    return x;
  }
};

LocalGlobalOptions fewSteps() {
  LocalGlobalOptions o;
  o.maxIterations = 20;
  return o;
}

TEST(RelaxThenSolve, AStoppedRelaxationEndsTheSolveAsUserAbort) {
  SolveFixture f;
  LocalGlobalOptions relax = fewSteps();
  relax.callback = [](const IterationSummary&) { return false; };  // a Ctrl-C at the first step
  Eigen::VectorXd x = f.x0;
  const SolveSequenceSummary s = relaxThenSolve(*f.relaxation, relax, f.problem, SolverOptions{},
                                                f.guard, {{f.anchors, 2, 1e-12}}, 8, x);
  EXPECT_TRUE(s.relaxation.stopped);
  EXPECT_EQ(s.summary.termination, Termination::UserAbort);
  EXPECT_TRUE(s.summary.iterations.empty()) << "no Levenberg-Marquardt step after a stop";
  EXPECT_EQ(s.constraintRounds, 0);
  EXPECT_EQ(x, f.relaxedAlone(relax)) << "x is where the relaxation stopped";
}

TEST(RelaxThenSolve, WithoutLevenbergMarquardtEachMultiplierRoundRelaxesAgain) {
  SolveFixture f;
  SolverOptions off;
  off.maxIterations = 0;
  const LocalGlobalOptions relax = fewSteps();
  LocalGlobalSummary once;
  {
    Eigen::VectorXd x = f.x0;
    once = f.relaxation->relax(relax, x);
  }
  Eigen::VectorXd x = f.x0;
  // A tolerance no anchored vertex meets after 20 steps: every round is used.
  const SolveSequenceSummary s =
      relaxThenSolve(*f.relaxation, relax, f.problem, off, f.guard, {{f.anchors, 2, 1e-12}}, 3, x);
  EXPECT_EQ(s.constraintRounds, 3);
  EXPECT_GT(s.relaxation.iterations, once.iterations) << "the rounds' relaxations are appended";
  EXPECT_TRUE(s.summary.iterations.empty());
  EXPECT_TRUE(s.summary.usable());
  EXPECT_NE(x, f.relaxedAlone(relax)) << "the rounds moved x on";
  // Without constraints the relaxation's shape is the result.
  Eigen::VectorXd y = f.x0;
  const SolveSequenceSummary plain =
      relaxThenSolve(*f.relaxation, relax, f.problem, off, f.guard, {}, 3, y);
  EXPECT_EQ(plain.constraintRounds, 0);
  EXPECT_EQ(y, f.relaxedAlone(relax));
}

TEST(RelaxThenSolve, LevenbergMarquardtGoesOnFromTheRelaxedShapeWithoutNewFolds) {
  SolveFixture f;
  const LocalGlobalOptions relax = fewSteps();
  const Eigen::VectorXd relaxed = f.relaxedAlone(relax);
  SolverOptions lm;
  lm.maxIterations = 30;
  Eigen::VectorXd x = f.x0;
  const SolveSequenceSummary s =
      relaxThenSolve(*f.relaxation, relax, f.problem, lm, f.guard, {}, 0, x);
  ASSERT_TRUE(s.summary.usable()) << s.summary.message;
  EXPECT_FALSE(s.summary.iterations.empty());
  // Its first cost is the relaxed shape's: it started there.
  EXPECT_DOUBLE_EQ(s.summary.initialCost, summaryWithoutSteps(f.problem, relaxed).initialCost);
  EXPECT_LT(s.summary.finalCost, s.summary.initialCost);
  EXPECT_LE(f.guard.count(x), f.guard.count(relaxed)) << "no step adds a fold";
}

}  // namespace
}  // namespace dform
