// raytracer: renders coursework JSON scenes with Vulkan compute shaders.
//   raytracer SCENE OUTPUT [options]   render to an image file (headless)
//   raytracer view SCENE [options]     interactive window
#include <cstring>

#include "app/Commands.hpp"

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "view") == 0) return runViewCommand(argc - 1, argv + 1);
  return runRenderCommand(argc, argv);
}
