// The inverse objective's one table of terms and weights (forward/term_table.h says what a row
// holds and who reads it).
#pragma once

#include "model/term_table.h"
#include "inverse/inverse_solve.h"

namespace dform {

/// The inverse objective (paper Eq. 6): every member of InverseWeights once, in the order the
/// terms are built, solved and reported.
const TermTable<InverseWeights>& inverseTerms();

}  // namespace dform
