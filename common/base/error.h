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

// A command line that cannot be used as given: an option's value out of its
// range or malformed, or options that do not go together. glint and glintd
// exit with 2 for it (as shells expect of a usage error) and with 1 for every
// other error: a scene, a file, a server.
class UsageError : public InputError {
 public:
  using InputError::InputError;
};

// Input that may be fine but cannot be taken now: what it needs is held by
// others for the moment (glintd's memory for the scenes being built). The
// same input may succeed later.
class BusyError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace glint
