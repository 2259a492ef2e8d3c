#include <gtest/gtest.h>

#include "core/status.hpp"

using namespace anitet;

TEST(Status, DefaultIsOk) {
  Status s;
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.code(), Error::Ok);
}

TEST(Status, ResultCarriesValueOrError) {
  Result<int> good(42);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(good.value(), 42);
  Result<int> bad(Error::Parse, "line 3: expected a number");
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), Error::Parse);
  EXPECT_EQ(bad.status().message(), "line 3: expected a number");
}

TEST(Status, ErrorCodesAreStable) {
  // These numbers are the C ABI's error codes: they must never change.
  EXPECT_EQ(static_cast<int>(Error::OpenBoundary), -13);
  EXPECT_EQ(static_cast<int>(Error::SelfIntersection), -17);
  EXPECT_EQ(static_cast<int>(Error::NotImplemented), -30);
  EXPECT_STREQ(error_name(Error::OpenBoundary), "open_boundary");
}
