#pragma once

#include <string>

namespace glint::bench {

// Many servers: scene 1 through 1, 2 and 3 real glintd processes on this
// host beside in process, then the client's tile dispatcher simulated in
// virtual time with scene 1's measured tile costs at 1920x1080: parallel
// efficiency for 1 to 64 servers against a static round robin, a 4x slow
// server, a lost one. Prints Markdown tables.
void distributedSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
