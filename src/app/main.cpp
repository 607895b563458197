// raytracer: renders coursework JSON scenes with Vulkan compute shaders.
//   raytracer SCENE OUTPUT [options]   render to an image file (headless)
//   raytracer view SCENE [options]     interactive window
//   raytracer merge PART.exr... OUT    combine split renders (--samples FROM:TO)
//   raytracer converge SCENE [options] error vs samples and time, per sampler
//   raytracer check SCENE              how the scene file is read, no render
#include <cstring>

#include "app/Commands.hpp"

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "view") == 0) return runViewCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "merge") == 0) return runMergeCommand(argc - 1, argv + 1);
  if (argc > 1 && std::strcmp(argv[1], "converge") == 0) {
    return runConvergeCommand(argc - 1, argv + 1);
  }
  if (argc > 1 && std::strcmp(argv[1], "check") == 0) return runCheckCommand(argc - 1, argv + 1);
  return runRenderCommand(argc, argv);
}
