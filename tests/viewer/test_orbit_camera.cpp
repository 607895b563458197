// The camera basis of both image-right conventions, and the viewer's orbit
// camera moving the way the image shows under each: a drag to the right
// turns the view the same way whether image right is forward x up (family
// A) or up x forward (family B).
#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include "scene/Scene.hpp"
#include "viewer/OrbitCamera.hpp"

using namespace rt;

namespace {

Camera lookingDownZ(ImageRight imageRight) {
  Camera camera;
  camera.position = {0, 0, -5};
  camera.forward = {0, 0, 1};
  camera.up = {0, 2, 0.5f};  // neither unit length nor orthogonal to forward
  camera.imageRight = imageRight;
  return camera;
}

}  // namespace

TEST_SUITE("viewer camera") {
  TEST_CASE("camera basis: up x forward mirrors image right and keeps image up") {
    CameraBasis a = cameraBasis(lookingDownZ(ImageRight::ForwardCrossUp));
    CameraBasis b = cameraBasis(lookingDownZ(ImageRight::UpCrossForward));
    CHECK(glm::length(a.right - glm::vec3(-1, 0, 0)) < 1e-6f);
    CHECK(glm::length(b.right - glm::vec3(1, 0, 0)) < 1e-6f);
    CHECK(glm::length(a.up - glm::vec3(0, 1, 0)) < 1e-6f);
    CHECK(glm::length(b.up - a.up) < 1e-6f);
    CHECK(glm::length(a.forward - b.forward) < 1e-6f);
  }

  TEST_CASE("orbit, pan and fly follow image right under both conventions") {
    for (ImageRight imageRight : {ImageRight::ForwardCrossUp, ImageRight::UpCrossForward}) {
      CAPTURE(int(imageRight));
      const Camera home = lookingDownZ(imageRight);
      const glm::vec3 right = cameraBasis(home).right;
      viewer::OrbitCamera camera;
      camera.setHome(home, {0, 0, 0}, 1.0f);
      camera.orbit(10.0f, 0.0f);  // positive: the camera moves to its right
      CHECK(glm::dot(glm::vec3(camera.camera().position - home.position), right) > 0.1f);
      camera.reset();
      camera.pan({10.0f, 0.0f}, 100.0f);  // the scene follows the cursor right
      CHECK(glm::dot(glm::vec3(camera.camera().position - home.position), right) < -0.01f);
      camera.reset();
      camera.fly({1.0f, 0.0f, 0.0f});
      CHECK(glm::length(glm::vec3(camera.camera().position - home.position) - right) < 1e-5f);
    }
  }
}
