// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/problem.h"

#include <cassert>
#include <vector>

namespace dform {

void ResidualTerm::secondDirectionalDerivative(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                               double* rvv) const {
  constexpr double h = 0.1;  // a step of 0.1 v: a central difference, O(h^2) off for quartic terms
  const int m = numResiduals();
  std::vector<double> plus(m), minus(m), centre(m);
  evaluate(x + h * v, plus.data(), nullptr);
  evaluate(x - h * v, minus.data(), nullptr);
  evaluate(x, centre.data(), nullptr);
  for (int i = 0; i < m; ++i) rvv[i] = (plus[i] - 2.0 * centre[i] + minus[i]) / (h * h);
}

LinearResidual::LinearResidual(Eigen::SparseMatrix<double, Eigen::RowMajor> M, Eigen::VectorXd b)
    : M_(std::move(M)), b_(std::move(b)) {
  M_.makeCompressed();
  assert(M_.rows() == b_.size() && "LinearResidual: M and b disagree in rows");
}

JacobianPattern LinearResidual::pattern() const {
  JacobianPattern p;
  p.rowStart.assign(M_.outerIndexPtr(), M_.outerIndexPtr() + M_.rows() + 1);
  p.cols.assign(M_.innerIndexPtr(), M_.innerIndexPtr() + M_.nonZeros());
  return p;
}

void LinearResidual::evaluate(const Eigen::VectorXd& x, double* r, double* J) const {
  Eigen::Map<Eigen::VectorXd>(r, M_.rows()) = M_ * x - b_;
  if (J) std::copy(M_.valuePtr(), M_.valuePtr() + M_.nonZeros(), J);
}

void LinearResidual::setTarget(Eigen::VectorXd b) {
  assert(b.size() == b_.size() && "LinearResidual: the target keeps its size");
  b_ = std::move(b);
}

void Problem::addTerm(std::string name, double weight, std::unique_ptr<ResidualTerm> term) {
  assert(weight >= 0.0 && "term weights are non-negative");
  terms_.push_back({std::move(name), weight, std::move(term)});
}

void Problem::holdConstant(const std::vector<int>& variables) {
  if (constant_.empty()) constant_.assign(std::size_t(numVariables_), false);
  for (int v : variables) {
    assert(v >= 0 && v < numVariables_ && "holdConstant: no such unknown");
    constant_[std::size_t(v)] = true;
  }
}

void Problem::setBlockSize(int size) {
  assert(size >= 1 && "setBlockSize: a block has at least one unknown");
  blockSize_ = size;
}

std::vector<double> Problem::termCosts(const Eigen::VectorXd& x) const {
  std::vector<double> costs;
  std::vector<double> r;
  for (const Entry& e : terms_) {
    r.resize(e.residual->numResiduals());
    e.residual->evaluate(x, r.data(), nullptr);
    double sum = 0.0;
    for (double v : r) sum += v * v;
    costs.push_back(e.weight * sum);
  }
  return costs;
}

}  // namespace dform
