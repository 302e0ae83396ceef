#pragma once

#include <string>

namespace glint::bench {

// Clients rendering through one real glintd process for a while: frames,
// errors, latency, and what the server process holds before, at its peak and
// after. Prints a Markdown table.
void loadSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
