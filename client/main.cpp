#include "client/cli.h"

int main(int argc, char** argv) { return glint::runCli(argc, argv); }
