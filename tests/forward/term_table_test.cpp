// forwardTerms: the forward objective's one table of terms and weights.
#include "dform/model/term_table.h"

#include <gtest/gtest.h>

#include "dform/forward/dform_from_shapes.h"
#include "model/term_table_checks.h"

namespace dform {
namespace {

// forwardTerms covers every member of ForwardWeights once, each row's linear flag agrees with the
// term its factory makes, a Problem and the relaxation's list built from it follow it, and a job's
// validation refuses a bad value of every weight (term_table_checks.h).
TEST(ForwardTerms, TableIsWholeAndAgreesWithItsTerms) {
  test::expectTermTableHolds(forwardTerms(), validateForwardJob);
}

}  // namespace
}  // namespace dform
