// Temporary until the viewer lands (src/viewer): reports that it is missing.
#include <cstdio>

#include "app/Commands.hpp"

int runViewCommand(int, char**) {
  std::fprintf(stderr, "error: the interactive viewer is not part of this build\n");
  return 1;
}
