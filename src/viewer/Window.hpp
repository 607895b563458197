// The viewer's GLFW window (no OpenGL context: GLFW_CLIENT_API = GLFW_NO_API)
// and the input it collected since the last frame. GLFW is initialised and
// terminated with the window; there is only ever one.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

struct GLFWwindow;

namespace rt::viewer {

// A key or click that happened since the last frame (edges, not held state).
struct KeyPress {
  int key = 0;  // GLFW_KEY_*
  int mods = 0;
};

struct Click {
  glm::dvec2 position{0.0};  // framebuffer pixels from the top-left corner
  int button = 0;            // GLFW_MOUSE_BUTTON_*
  int mods = 0;
};

struct InputEvents {
  glm::dvec2 orbitDrag{0.0};  // framebuffer pixels dragged with the left button
  glm::dvec2 panDrag{0.0};    // ... with the middle or right button
  double scroll = 0.0;        // wheel steps, positive = away from the user
  std::vector<KeyPress> keys;
  std::vector<Click> clicks;
};

class Window {
 public:
  Window(uint32_t width, uint32_t height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void resize(uint32_t width, uint32_t height);
  void requestClose();

  // Instance extensions the surface needs, and the surface itself.
  static std::vector<const char*> requiredInstanceExtensions();
  VkSurfaceKHR createSurface(VkInstance instance) const;

  // Framebuffer size in pixels (0 x 0 while minimised).
  glm::uvec2 framebufferSize() const;

  // Processes window events: without waiting, or up to `seconds` for one.
  void pollEvents();
  void waitEvents(double seconds);

  // The input collected since the last call; `uiHasMouse`/`uiHasKeyboard`
  // drop what the overlay consumed.
  InputEvents takeInput(bool uiHasMouse, bool uiHasKeyboard);
  bool keyHeld(int key) const;
  // Whether anything happened (input, resize, expose) since the last call:
  // an idle viewer redraws only then.
  bool takeActivity();

 private:
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onActivity(GLFWwindow* window);
  glm::dvec2 cursorInFramebufferPixels() const;

  GLFWwindow* window_ = nullptr;
  InputEvents pending_;
  glm::dvec2 lastCursor_{0.0};
  bool active_ = true;
};

}  // namespace rt::viewer
