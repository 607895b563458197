#include "viewer/Window.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"
#include "viewer/ThirdParty.hpp"

namespace rt::viewer {
namespace {

void onGlfwError(int code, const char* description) {
  std::fprintf(stderr, "glfw error %d: %s\n", code, description);
}

Window& owner(GLFWwindow* window) {
  return *static_cast<Window*>(glfwGetWindowUserPointer(window));
}

}  // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    throw Error("cannot open a window: GLFW initialisation failed (is DISPLAY set? try xvfb-run)");
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("cannot open a window: GLFW found no Vulkan loader");
  }
  // Vulkan draws into the window; GLFW must not create an OpenGL context.
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(),
                             nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Error(fmt::format("cannot open a {}x{} window", width, height));
  }
  glfwSetWindowUserPointer(window_, this);
  // Installed before ImGui's GLFW backend, which chains to them.
  glfwSetMouseButtonCallback(window_, onMouseButton);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetKeyCallback(window_, onKey);
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double, double) { onActivity(w); });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { onActivity(w); });
  glfwSetWindowRefreshCallback(window_, onActivity);
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int) { onActivity(w); });
  lastCursor_ = cursorInFramebufferPixels();
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }

void Window::resize(uint32_t width, uint32_t height) {
  glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
}

void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

std::vector<const char*> Window::requiredInstanceExtensions() {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw Error("GLFW cannot create Vulkan window surfaces on this system");
  return std::vector<const char*>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  vkCheck(glfwCreateWindowSurface(instance, window_, nullptr, &surface), "glfwCreateWindowSurface");
  return surface;
}

glm::uvec2 Window::framebufferSize() const {
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {static_cast<uint32_t>(std::max(width, 0)), static_cast<uint32_t>(std::max(height, 0))};
}

void Window::pollEvents() { glfwPollEvents(); }

void Window::waitEvents(double seconds) { glfwWaitEventsTimeout(seconds); }

glm::dvec2 Window::cursorInFramebufferPixels() const {
  double x = 0.0;
  double y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  // Cursor positions are in screen coordinates; on HiDPI screens the
  // framebuffer has more pixels than that.
  int windowWidth = 1;
  int windowHeight = 1;
  glfwGetWindowSize(window_, &windowWidth, &windowHeight);
  glm::uvec2 framebuffer = framebufferSize();
  return {x * framebuffer.x / std::max(windowWidth, 1),
          y * framebuffer.y / std::max(windowHeight, 1)};
}

InputEvents Window::takeInput(bool uiHasMouse, bool uiHasKeyboard) {
  InputEvents events = std::move(pending_);
  pending_ = {};
  glm::dvec2 cursor = cursorInFramebufferPixels();
  glm::dvec2 delta = cursor - lastCursor_;
  lastCursor_ = cursor;
  if (uiHasMouse) {
    events.scroll = 0.0;
    events.clicks.clear();
  } else {
    bool ctrl = keyHeld(GLFW_KEY_LEFT_CONTROL) || keyHeld(GLFW_KEY_RIGHT_CONTROL);
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !ctrl) {
      events.orbitDrag += delta;
    }
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS ||
        glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
      events.panDrag += delta;
    }
  }
  if (uiHasKeyboard) events.keys.clear();
  return events;
}

bool Window::keyHeld(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

bool Window::takeActivity() { return std::exchange(active_, false); }

void Window::onActivity(GLFWwindow* window) { owner(window).active_ = true; }

void Window::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Window& self = owner(window);
  self.active_ = true;
  if (action != GLFW_PRESS) return;
  self.pending_.clicks.push_back({self.cursorInFramebufferPixels(), button, mods});
}

void Window::onScroll(GLFWwindow* window, double, double dy) {
  owner(window).pending_.scroll += dy;
}

void Window::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  owner(window).active_ = true;
  if (action != GLFW_PRESS) return;
  owner(window).pending_.keys.push_back({key, mods});
}

}  // namespace rt::viewer
