#include "app/cli.hpp"

#include <cstdio>

namespace gf::app {
int runCommandLine(int argc, char** argv) {
  std::puts("grainflow");
  return 0;
}
}  // namespace gf::app
