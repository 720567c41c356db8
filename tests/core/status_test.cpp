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

}  // namespace
}  // namespace dform
