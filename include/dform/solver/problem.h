// SPDX-License-Identifier: GPL-3.0-or-later
// A sparse nonlinear least-squares problem: minimise f(x) = sum_t w_t * ||r_t(x)||^2 over x.
// The solver knows nothing of D-Forms: callers build residual terms over a flat variable vector.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace dform {

/// Sparsity pattern of a Jacobian in compressed rows: row i's nonzeros are at columns
/// cols[rowStart[i]] .. cols[rowStart[i+1]-1], in the order their values are written.
struct JacobianPattern {
  std::vector<int> rowStart{0};  ///< where each row's columns start in `cols`, then the end
  std::vector<int> cols;         ///< the nonzeros' columns, row after row
  /// The number of rows.
  int rows() const { return int(rowStart.size()) - 1; }
};

/// A block of residuals whose Jacobian has a fixed sparsity pattern.
class ResidualTerm {
 public:
  virtual ~ResidualTerm() = default;
  /// The Jacobian's pattern; called once.
  virtual JacobianPattern pattern() const = 0;
  /// The number of residuals (= pattern().rows(), without building the pattern).
  virtual int numResiduals() const = 0;
  /// Writes the residuals into r (pattern().rows() values) and, if J is not null, the Jacobian
  /// values in pattern order.
  virtual void evaluate(const Eigen::VectorXd& x, double* r, double* J) const = 0;
  /// True when the Jacobian does not depend on x; its normal-matrix part is then assembled once.
  virtual bool isLinear() const { return false; }
  /// Writes the second directional derivative of the residuals along v, r''(x)[v, v], into rvv
  /// (numResiduals() values): the curvature that geodesic acceleration corrects for. The default
  /// is the central difference (r(x + h v) - 2 r(x) + r(x - h v)) / h^2 with h = 0.1, exact for
  /// residuals that are at most quadratic; terms override it with the exact value.
  virtual void secondDirectionalDerivative(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                           double* rvv) const;
};

/// Residuals r(x) = M x - b for a constant sparse M (#rows by #variables).
class LinearResidual : public ResidualTerm {
 public:
  /// The residuals M x - b; b has M's number of rows.
  LinearResidual(Eigen::SparseMatrix<double, Eigen::RowMajor> M, Eigen::VectorXd b);
  JacobianPattern pattern() const override;
  int numResiduals() const override { return int(M_.rows()); }
  void evaluate(const Eigen::VectorXd& x, double* r, double* J) const override;
  bool isLinear() const override { return true; }
  void secondDirectionalDerivative(const Eigen::VectorXd&, const Eigen::VectorXd&,
                                   double* rvv) const override {
    std::fill(rvv, rvv + M_.rows(), 0.0);
  }

  /// M.
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& matrix() const { return M_; }
  /// b, the value M x is driven towards.
  const Eigen::VectorXd& target() const { return b_; }
  /// Moves the target b (same size); the Jacobian is unchanged, so a solver built on the problem
  /// stays valid. Used for multiplier updates of constraint-like terms.
  void setTarget(Eigen::VectorXd b);

 private:
  Eigen::SparseMatrix<double, Eigen::RowMajor> M_;
  Eigen::VectorXd b_;
};

/// The objective: named, weighted terms over `numVariables` unknowns.
class Problem {
 public:
  /// An objective without terms over `numVariables` unknowns.
  explicit Problem(int numVariables) : numVariables_(numVariables) {}

  /// Adds w * ||r(x)||^2 to the objective. Weights must be non-negative.
  void addTerm(std::string name, double weight, std::unique_ptr<ResidualTerm> term);

  int numVariables() const { return numVariables_; }   ///< the length of x
  int numTerms() const { return int(terms_.size()); }  ///< the terms added, in order
  /// Term t's name, as summaries and reports list it.
  const std::string& termName(int t) const { return terms_[t].name; }
  double termWeight(int t) const { return terms_[t].weight; }  ///< term t's weight w_t
  /// Term t's residuals.
  const ResidualTerm& term(int t) const { return *terms_[t].residual; }

  /// Per-term costs w_t * ||r_t(x)||^2 at x.
  std::vector<double> termCosts(const Eigen::VectorXd& x) const;

  /// Holds these unknowns at their starting values: the solver never moves them (in the spirit of
  /// Ceres' SetParameterBlockConstant). Terms may still read them.
  void holdConstant(const std::vector<int>& variables);
  const std::vector<bool>& constantMask() const { return constant_; }  ///< empty when none are

  /// Says that the unknowns come in consecutive blocks of `size` that the terms couple together
  /// (a mesh vertex's coordinates): the factorisation's ordering then orders whole blocks, which
  /// takes a fraction of the time. A hint only; the solution does not depend on it beyond rounding.
  void setBlockSize(int size);
  int blockSize() const { return blockSize_; }  ///< the hint of setBlockSize, 1 when not given

 private:
  struct Entry {
    std::string name;
    double weight;
    std::unique_ptr<ResidualTerm> residual;
  };
  int numVariables_;
  std::vector<Entry> terms_;
  std::vector<bool> constant_;
  int blockSize_ = 1;
};

}  // namespace dform
