#include "client/cli.h"
#include "common/base/heap_tuning.h"

int main(int argc, char** argv) {
  glint::keepFreedMemoryForReuse();
  return glint::runCli(argc, argv);
}
