#pragma once

#include <string>

namespace glint::server {

// One line on stderr with a timestamp; safe from any thread. The line is
// made printable (common/base/printable.h): what a client sent and the server
// quotes cannot break it in two or drive a terminal.
void logLine(const std::string& line);

// Quiet servers (tests) log nothing.
void setLogging(bool enabled);

}  // namespace glint::server
