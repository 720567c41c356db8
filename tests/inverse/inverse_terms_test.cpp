// SPDX-License-Identifier: GPL-3.0-or-later
// inverseTerms: the inverse objective's one table of terms and weights.
#include <gtest/gtest.h>

#include "dform/model/term_table.h"
#include "model/term_table_checks.h"

namespace dform {
namespace {

// inverseTerms covers every member of InverseWeights once, each row's linear flag agrees with the
// term its factory makes, and a Problem and the relaxation's list built from it follow it
// (term_table_checks.h). The settings table's rows of the weights refuse a bad value of each
// (pipeline's SettingsTable tests).
TEST(InverseTerms, TableIsWholeAndAgreesWithItsTerms) {
  test::expectTermTableHolds(inverseTerms());
}

}  // namespace
}  // namespace dform
