#pragma once

#include <string>

namespace glint::server {

// One line on stderr with a timestamp; safe from any thread.
void logLine(const std::string& line);

// Quiet servers (tests) log nothing.
void setLogging(bool enabled);

}  // namespace glint::server
