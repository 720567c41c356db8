// SPDX-License-Identifier: GPL-3.0-or-later
// forwardTerms: the forward objective's one table of terms and weights.
#include "dform/model/term_table.h"

#include <gtest/gtest.h>

#include "model/term_table_checks.h"

namespace dform {
namespace {

// forwardTerms covers every member of ForwardWeights once, each row's linear flag agrees with the
// term its factory makes, and a Problem and the relaxation's list built from it follow it
// (term_table_checks.h). The settings table's rows of the weights refuse a bad value of each
// (pipeline's SettingsTable tests).
TEST(ForwardTerms, TableIsWholeAndAgreesWithItsTerms) {
  test::expectTermTableHolds(forwardTerms());
}

}  // namespace
}  // namespace dform
