#include "viewer/HotReload.hpp"

namespace rt::viewer {
namespace {

bool isShaderSource(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  return extension == ".glsl" || extension == ".comp" || extension == ".h";
}

// Files beside the scene that it may read: models, their buffers and
// material libraries. Images are not among them: the viewer saves its own
// images there, and a save must not restart the render.
bool isModelInput(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (const char* known : {".obj", ".mtl", ".ply", ".gltf", ".glb", ".bin"}) {
    if (extension == known) return true;
  }
  return false;
}

}  // namespace

HotReload::HotReload(const std::filesystem::path& shaderDir, const std::filesystem::path& scenePath)
    : shaderDir_(shaderDir), sceneFile_(scenePath.filename()) {
  watcher_.watchFolder(shaderDir_);
  std::filesystem::path sceneFolder = scenePath.parent_path();
  watcher_.watchFolder(sceneFolder.empty() ? std::filesystem::path(".") : sceneFolder);
}

HotReload::Due HotReload::poll(Clock::time_point now) {
  for (const std::filesystem::path& file : watcher_.poll()) {
    if (isShaderSource(file) && file.parent_path() == shaderDir_) {
      shaderChanges_.notify(now);
    } else if (file.filename() == sceneFile_ || isModelInput(file)) {
      sceneChanges_.notify(now);
    }
  }
  return {shaderChanges_.ready(now), sceneChanges_.ready(now)};
}

}  // namespace rt::viewer
