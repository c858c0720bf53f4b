// The message of the kneesim::InputError a call throws, for the bad-input tests of every
// suite (design.md: one sentence naming file, field, value and allowed range).
#pragma once

#include <string>

#include "engine/errors.h"

namespace kneesim::test {

// the message of the InputError thrown by f(), or "" when f() returns normally (other
// exceptions propagate, so a wrong error type fails the test)
template <class F>
std::string input_error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace kneesim::test
