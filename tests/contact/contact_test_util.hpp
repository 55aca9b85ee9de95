#pragma once
// Test helpers shared by the contact tests.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace contact_test {

// Expect `f()` to throw std::invalid_argument whose message contains every given fragment
// (the type/function, the parameter name, the offending value).
template <class F>
void expect_invalid_argument(F&& f, std::initializer_list<const char*> fragments) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const char* fragment : fragments)
      EXPECT_NE(what.find(fragment), std::string::npos)
          << "message '" << what << "' lacks '" << fragment << "'";
  }
}

}  // namespace contact_test
