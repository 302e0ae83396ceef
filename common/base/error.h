#pragma once

#include <stdexcept>
#include <string>

namespace glint {

// Bad input from outside the program (scene file, command line, network
// bytes). The message names the place ("objects[3].radius: must be > 0") and
// says what is wrong; it is caught at the program's boundary and printed.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Input that may be fine but cannot be taken now: what it needs is held by
// others for the moment (glintd's memory for the scenes being built). The
// same input may succeed later.
class BusyError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace glint
