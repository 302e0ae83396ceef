#pragma once

#include "common/base/error.h"

namespace glint {

// A command line that cannot be used as given: an option's value out of its
// range or malformed, or options that do not go together. glint exits with
// 2 for it (as shells expect of a usage error) and with 1 for every other
// error: a scene, a file, a server.
class UsageError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace glint
