// Scripted sessions (--camera-path FILE): a text file with one step per line,
// each applied at the start of one frame ('#' starts a comment):
//   orbit YAW PITCH        degrees (positive: camera moves right / down)
//   pan DX DY              pixels, like a middle-button drag
//   zoom STEPS             wheel steps (positive: closer)
//   fly RIGHT UP FORWARD   in scene radii
//   lookat PX PY PZ TX TY TZ   camera position and the point it looks at
//   lens RADIUS DISTANCE   thin-lens aperture radius and focus distance
//   focus X Y              focus on the surface under render pixel (X, Y)
//   reset                  back to the scene's camera
//   resize W H             resizes the window (the render follows)
//   screenshot FILE        writes the image presented at the end of this frame
//   save FILE              writes the accumulated render (like key S) to FILE
//   wait [N]               N frames (default 1) without a change
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rt::viewer {

struct PathStep {
  enum class Kind {
    Orbit,
    Pan,
    Zoom,
    Fly,
    LookAt,
    Lens,
    Focus,
    Reset,
    Resize,
    Screenshot,
    Save,
    Wait
  };
  Kind kind = Kind::Wait;
  std::vector<float> values;
  std::filesystem::path file;  // screenshot, save
  uint32_t frames = 1;         // wait
  int line = 0;
};

// Throws rt::Error "FILE:LINE: message" on unknown steps or bad numbers.
std::vector<PathStep> loadCameraPath(const std::filesystem::path& file);

// Hands out the steps frame by frame.
class CameraPathPlayer {
 public:
  CameraPathPlayer() = default;
  explicit CameraPathPlayer(std::vector<PathStep> steps) : steps_(std::move(steps)) {}

  // The step for the next frame, or nullptr once a wait or the path is over.
  const PathStep* next();
  bool finished() const { return index_ >= steps_.size(); }

 private:
  std::vector<PathStep> steps_;
  size_t index_ = 0;
  uint32_t waited_ = 0;
};

}  // namespace rt::viewer
