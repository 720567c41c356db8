// SPDX-License-Identifier: GPL-3.0-or-later
// The one table per objective of its terms and their weights: forward modelling's (forwardTerms)
// and inverse modelling's (inverseTerms). The settings table's weight rows (pipeline/settings.h:
// job files, the command line, Python, the studio, the range check), report.json's term names
// and the solves (their Problem and their local-global relaxation's
// linear terms) all loop over it. To add a term: a member in the mode's weights struct
// (model/weights.h) and a row in its table (its name, that member, its factory, whether it is
// linear); the factory reads TermInputs (model/terms.h), which grows a field if it needs one.
#pragma once

#include <cassert>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dform/model/terms.h"
#include "dform/model/weights.h"
#include "dform/solver/problem.h"
#include "dform/solver/solver.h"

namespace dform {

/// One term of an objective and its weight.
template <typename Weights>
struct TermRow {
  std::string name;         ///< as job files, the settings table and report.json give it
  double Weights::*weight;  ///< its member of the weights struct
  std::string help;         ///< what the weight weighs, one line (the settings table's help)
  /// Makes the term; null for a weight that switches an exact constraint instead of weighting a
  /// term of its own (forward's alignment: the seam closed; inverse's closeness: held on the
  /// curve).
  std::unique_ptr<ResidualTerm> (*make)(const TermInputs&);
  /// The term is a LinearResidual, which the local-global relaxation takes as it is (the isometry
  /// term enters the relaxation in its projective form, through the edges, instead).
  bool linear;
};

template <typename Weights>
using TermTable = std::vector<TermRow<Weights>>;

/// The forward objective (paper Eq. 1-5): every member of ForwardWeights once, in the order the
/// terms are built, solved and reported.
const TermTable<ForwardWeights>& forwardTerms();

/// The inverse objective (paper Eq. 6): every member of InverseWeights once, in the order the
/// terms are built, solved and reported.
const TermTable<InverseWeights>& inverseTerms();

/// The tables' factories on terms.h's builders (inverse modelling's table shares the first three):
/// isometry (Eq. 1), surface smoothness in 3D and flat (Eq. 4), the boundary fix of the anchored
/// vertices (Eq. 3) and seam smoothness (Eq. 5).
std::unique_ptr<ResidualTerm> isometryTerm(const TermInputs& in);
std::unique_ptr<ResidualTerm> smooth3dTerm(const TermInputs& in);
std::unique_ptr<ResidualTerm> smooth2dTerm(const TermInputs& in);
std::unique_ptr<ResidualTerm> boundaryFixTerm(const TermInputs& in);
std::unique_ptr<ResidualTerm> seamTerm(const TermInputs& in);

/// Each row's term made from `inputs`, in the table's order (null where a row makes none).
template <typename Weights>
std::vector<std::unique_ptr<ResidualTerm>> makeTerms(const TermTable<Weights>& table,
                                                     const TermInputs& inputs) {
  std::vector<std::unique_ptr<ResidualTerm>> terms;
  for (const TermRow<Weights>& row : table) terms.push_back(row.make ? row.make(inputs) : nullptr);
  return terms;
}

/// The linear terms with their weights, in the table's order: the local-global relaxation's list.
/// `terms` are makeTerms' and must outlive the list.
template <typename Weights>
std::vector<std::pair<double, const LinearResidual*>> linearTerms(
    const TermTable<Weights>& table, const std::vector<std::unique_ptr<ResidualTerm>>& terms,
    const Weights& weights) {
  std::vector<std::pair<double, const LinearResidual*>> linear;
  for (std::size_t k = 0; k < table.size(); ++k)
    if (table[k].linear) {
      assert(dynamic_cast<const LinearResidual*>(terms[k].get()) &&
             "a row marked linear makes a LinearResidual");
      linear.emplace_back(weights.*table[k].weight,
                          static_cast<const LinearResidual*>(terms[k].get()));
    }
  return linear;
}

/// Moves each of makeTerms' terms into `problem` under its row's name and weight, in the table's
/// order.
template <typename Weights>
void addTerms(Problem& problem, const TermTable<Weights>& table,
              std::vector<std::unique_ptr<ResidualTerm>>& terms, const Weights& weights) {
  for (std::size_t k = 0; k < table.size(); ++k)
    if (terms[k]) problem.addTerm(table[k].name, weights.*table[k].weight, std::move(terms[k]));
}

/// The row of the weight `member`: the table has one for every member.
template <typename Weights>
std::size_t rowOf(const TermTable<Weights>& table, double Weights::*member) {
  std::size_t k = 0;
  while (k < table.size() && table[k].weight != member) ++k;
  assert(k < table.size() && "every weight has its row");
  return k;
}

/// The row named `name`, or null.
template <typename Weights>
const TermRow<Weights>* findTerm(const TermTable<Weights>& table, const std::string& name) {
  for (const TermRow<Weights>& row : table)
    if (row.name == name) return &row;
  return nullptr;
}

}  // namespace dform
