#pragma once
// Shared by the scene tests: capture the message of an expected InputError.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/error.hpp"

namespace erythro::scene::testing {

// The InputError message of `f`, or a test failure if it does not throw one.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

}  // namespace erythro::scene::testing

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << "message: " << (text)
