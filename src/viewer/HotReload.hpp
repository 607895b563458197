// What the viewer's hot reload knows between frames: the watched folders,
// the debounced saves of shaders and of the scene file (or of the models and
// material libraries beside it: .obj, .mtl, .ply, .gltf, .glb, .bin), and a scene edit
// that waits for shaders that build.
#pragma once

#include <chrono>
#include <filesystem>

#include "viewer/FileWatcher.hpp"

namespace rt::viewer {

class HotReload {
 public:
  using Clock = std::chrono::steady_clock;

  // Watches the shader folder and the scene file's folder; throws rt::Error
  // when one cannot be watched.
  HotReload(const std::filesystem::path& shaderDir, const std::filesystem::path& scenePath);

  struct Due {
    bool shaders = false;
    bool scene = false;
  };
  // The reloads whose files were saved and then left alone for a moment.
  Due poll(Clock::time_point now);
  // When the first save of the batch that became due was seen.
  Clock::time_point shadersSavedAt() const { return shaderChanges_.firstChange(); }
  Clock::time_point sceneSavedAt() const { return sceneChanges_.firstChange(); }

  // A scene edit loaded but could not be built with the current shaders:
  // it is tried again once shaders reload.
  bool sceneWaitsForShaders = false;

 private:
  std::filesystem::path shaderDir_;
  std::filesystem::path sceneFile_;  // file name only: saves are matched by name
  FileWatcher watcher_;
  Debouncer shaderChanges_{std::chrono::milliseconds(50)};
  Debouncer sceneChanges_{std::chrono::milliseconds(50)};
};

}  // namespace rt::viewer
