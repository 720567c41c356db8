// inverseTerms: the inverse objective's one table of terms and weights.
#include <gtest/gtest.h>

#include "dform/inverse/pieces_from_curve.h"
#include "dform/model/term_table.h"
#include "model/term_table_checks.h"

namespace dform {
namespace {

// inverseTerms covers every member of InverseWeights once, each row's linear flag agrees with the
// term its factory makes, a Problem and the relaxation's list built from it follow it, and a job's
// validation refuses a bad value of every weight (term_table_checks.h).
TEST(InverseTerms, TableIsWholeAndAgreesWithItsTerms) {
  test::expectTermTableHolds(inverseTerms(), validateInverseJob);
}

}  // namespace
}  // namespace dform
