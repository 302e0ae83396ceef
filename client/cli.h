#pragma once

namespace glint {

// The `glint` command line: parses the arguments, runs the subcommand and
// returns the process exit status (0 success, 1 failed run, 2 bad usage).
// Every error is one line on stderr that says what is wrong.
int runCli(int argc, char** argv);

}  // namespace glint
