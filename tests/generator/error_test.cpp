// The two error kinds: a user's mistake and a broken invariant are told apart by type.
#include "generator/error.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
namespace {

TEST(Error, InputErrorsCarryTheirMessage) {
  try {
    fail_input("bad SPEC '1,x'");
    FAIL() << "fail_input returned";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "bad SPEC '1,x'");
  }
}

TEST(Error, InternalErrorsAreNotInputErrors) {
  EXPECT_THROW(fail_internal("broken"), InternalError);
  try {
    fail_internal("broken");
  } catch (const InputError&) {
    FAIL() << "an internal error was reported as the user's";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "broken");
  }
}

}  // namespace
}  // namespace boxgen::generator
