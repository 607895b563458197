// The test runner: doctest's own, plus one line saying why the test cases
// that read ../shared are skipped when it is missing.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

#include "support/TestSupport.hpp"

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  if (!rt::test::sharedDir()) {
    std::fprintf(stderr,
                 "rt_tests: no shared folder at %s: the test cases that read it are skipped\n",
                 std::getenv("RT_SHARED_DIR") ? std::getenv("RT_SHARED_DIR") : RT_SHARED_DIR);
  }
  return context.run();
}
