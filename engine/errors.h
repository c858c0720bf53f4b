// Error tiers (design.md): InputError is thrown only while loading input (config, mesh, table,
// CLI) and carries one sentence naming the file, field, value and allowed range. Numerical
// trouble during a step never throws: it sets a StepStatus (engine/step.h).
#pragma once

#include <stdexcept>
#include <string>

namespace kneesim {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace kneesim
