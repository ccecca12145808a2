// Test support: what an expected exception says, for the tests of one-line errors. Header-only:
// tests of several stages include it.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

namespace vaegail {

// what() of the exception `call` throws, which must be one line; a failure when it throws none.
template <class F>
std::string one_line_error_of(F call) {
  try {
    call();
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << "no exception";
  return {};
}

// what() of the exception `call` throws, or "" when it throws none (for tests where both happen).
template <class F>
std::string error_of(F call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace vaegail
