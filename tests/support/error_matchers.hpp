// GoogleTest predicates for the core's refusals: a patchspin::Error whose
// message names the problem.
#pragma once

#include <patchspin/types.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace patchspin::testing {

// The call throws patchspin::Error and its message contains one of `words`
// (case-insensitive).
inline ::testing::AssertionResult throwsNaming(const std::function<void()>& call,
                                               const std::vector<std::string>& words) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  try {
    call();
  } catch (const Error& e) {
    const std::string msg = lower(e.what());
    for (const std::string& w : words)
      if (msg.find(lower(w)) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "message does not name the problem: " << e.what();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a non-Error exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

// True if f throws patchspin::Error with a message naming the pressure as
// not finite.
template <class F>
::testing::AssertionResult refusedAsNotFinite(F f) {
  try {
    f();
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.find("not finite") == std::string::npos)
      return ::testing::AssertionFailure() << "Error without \"not finite\": " << what;
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no Error";
}

}  // namespace patchspin::testing
