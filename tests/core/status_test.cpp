// SPDX-License-Identifier: GPL-3.0-or-later
// Result<T>: a value, or the Status that says why there is none; reading the value of an error is
// a checked failure in every build, as std::expected's.
#include "dform/core/status.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

namespace dform {
namespace {

TEST(Result, HoldsItsValue) {
  Result<std::string> r(std::string("outline"));
  ASSERT_TRUE(r.isOk());
  EXPECT_EQ(r.value(), "outline");
  EXPECT_EQ(std::move(r).value(), "outline");
}

TEST(Result, ReadingTheValueOfAnErrorThrowsWithItsStatus) {
  Result<std::string> r(Status(ErrorCode::InputInvalid, "a.svg: the outline is open"));
  ASSERT_FALSE(r.isOk());
  try {
    (void)r.value();
    FAIL() << "value() of an error returned";
  } catch (const BadResultAccess& e) {
    EXPECT_EQ(e.status().code(), ErrorCode::InputInvalid);
    EXPECT_NE(std::string(e.what()).find("a.svg: the outline is open"), std::string::npos)
        << e.what();
  }
  const Result<std::string>& constant = r;
  EXPECT_THROW((void)constant.value(), BadResultAccess);
  EXPECT_THROW((void)std::move(r).value(), BadResultAccess);
  EXPECT_THROW((void)r.value(), std::logic_error);  // catchable as the standard's logic errors
}

// A Result made from an ok Status has no value to give: it is an error (Internal) rather than a
// default-made value that would read as a result.
TEST(Result, MadeFromAnOkStatusIsAnInternalError) {
  const Result<double> r(Status::ok());
  EXPECT_FALSE(r.isOk());
  EXPECT_EQ(r.status().code(), ErrorCode::Internal);
  EXPECT_THROW((void)r.value(), BadResultAccess);
}

// The value type needs no default constructor: an error holds no value at all.
TEST(Result, HoldsATypeWithoutADefaultConstructor) {
  struct Length {
    explicit Length(double mm) : mm(mm) {}
    double mm;
  };
  const Result<Length> made(Length(3.5));
  ASSERT_TRUE(made.isOk());
  EXPECT_EQ(made.value().mm, 3.5);
  const Result<Length> failed(Status(ErrorCode::Usage, "no length"));
  EXPECT_FALSE(failed.isOk());
}

}  // namespace
}  // namespace dform
