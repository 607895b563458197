// The viewer's hot reload: which saved files reload the shaders, which the
// scene (the scene file, and the models and material libraries beside it),
// and which nothing (images, such as the viewer's own saves).
#include <doctest/doctest.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "support/TestSupport.hpp"
#include "viewer/HotReload.hpp"

namespace {

using rt::test::TempDir;
using rt::viewer::HotReload;

// What is due once the watcher has seen `save`'s files and the debounce
// has passed (inotify delivers the events at once; the loop allows a slow
// machine a second).
HotReload::Due dueAfter(HotReload& reload, const std::function<void()>& save) {
  save();
  HotReload::Clock::time_point now = HotReload::Clock::now();
  HotReload::Due due;
  for (int i = 0; i < 100 && !due.scene && !due.shaders; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    reload.poll(now);
    due = reload.poll(now + std::chrono::seconds(1));
    now += std::chrono::seconds(2);
  }
  return due;
}

}  // namespace

TEST_SUITE("viewer hot reload") {
  TEST_CASE("the scene reloads for its file, its models and material libraries; not for images") {
    TempDir dir;
    dir.write("shaders/trace.comp", "// kernel\n");
    const std::filesystem::path scene = dir.write("scene/room.json", "{}");
    HotReload reload(dir.path() / "shaders", scene);

    HotReload::Due due = dueAfter(reload, [&] { dir.write("scene/room.json", "{ }"); });
    CHECK(due.scene);
    CHECK_FALSE(due.shaders);
    for (const char* model : {"scene/box.mtl", "scene/box.obj", "scene/bunny.ply",
                              "scene/model.gltf", "scene/model.bin"}) {
      CAPTURE(model);
      due = dueAfter(reload, [&] { dir.write(model, "x"); });
      CHECK(due.scene);
      CHECK_FALSE(due.shaders);
    }
    due = dueAfter(reload, [&] { dir.write("shaders/shading.glsl", "// edit\n"); });
    CHECK(due.shaders);
    CHECK_FALSE(due.scene);
    // The viewer's saved images, notes and other scenes beside it: nothing.
    for (const char* other : {"scene/room-0001.png", "scene/notes.txt", "scene/other.json"}) {
      CAPTURE(other);
      due = dueAfter(reload, [&] { dir.write(other, "x"); });
      CHECK_FALSE(due.scene);
      CHECK_FALSE(due.shaders);
    }
  }
}
