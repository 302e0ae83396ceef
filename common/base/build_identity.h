#pragma once

#include <string>

namespace glint {

// What decides the pixels this build makes: the tracer's version, the
// compiler and the flags that change floating point. Two builds with the same
// identity give byte-identical tiles; glint refuses a glintd whose identity
// differs from its own rather than risk seams in a frame (docs/distributed.md).
// "pixels-1 gcc-12.2.0 3f2a..." (the hash covers the flags).
const std::string& buildIdentity();

}  // namespace glint
