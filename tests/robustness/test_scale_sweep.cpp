// One scene rendered at many scales and distances from the world origin.
//
// What is achievable: scene coordinates are float32. Scaling by a power of
// two is exact, and so is every float operation on the scaled numbers, so a
// renderer whose tolerances are all relative (ray offsets in
// shaders/geometry.glsl) gives the same image bit for bit. Sweep: 2^-14
// (6e-5) to 2^20 (1e6).
// Translation is not exact in general: at 1e6 the float spacing is 1/16, at
// 4e6 it is 1/4, so the scene a file describes there is itself moved by up
// to half that. Flattening relative to the camera (src/render/FlatScene.cpp)
// makes the GPU see exactly the differences of the given floats, so a
// translated scene renders bit for bit like the unit-scale scene with the
// same rounded coordinates. Sweep: offsets from 1e3 to 4e6 per axis, at
// scales 1 and 2^-10. The unit scene's coordinates are multiples of
// 1/16, so translations up to 1e6 do not round them and change nothing.
// Against the unrounded unit scene, a decimal scale (1e-4 to 1e6, relative
// rounding 6e-8) may change only pixels whose sample lands within rounding
// of an edge (at most 1% of pixels by more than 1e-3), and a move to 4e6
// shifts edges by up to 1/8 unit, about a pixel here: PSNR (8-bit) above
// 25 dB (measured 29.6 dB), which a one-pixel shift of edges allows.
#include <doctest/doctest.h>

#include <algorithm>
#include <functional>

#include "robustness/RobustnessSupport.hpp"

using namespace rt;
using namespace rt::test;

namespace {

// Where a unit-scene point goes, and how lengths scale.
struct Placement {
  std::function<glm::vec3(glm::dvec3)> point;
  double scale = 1.0;
};

// Rounds to float. volatile: GCC 12's SLP vectorizer at -O2 was seen to drop
// a double -> float -> double round trip, which is the point here.
glm::vec3 roundedToFloat(glm::dvec3 v) {
  volatile float x = float(v.x), y = float(v.y), z = float(v.z);
  return {x, y, z};
}

Placement scaledAndMoved(double scale, glm::dvec3 offset) {
  return {[=](glm::dvec3 p) { return roundedToFloat(scale * p + offset); }, scale};
}

// The unit-scale scene with the coordinates the placed scene rounded to:
// (float(s p + T) - T) / s, exact for power-of-two s.
Placement roundedLike(double scale, glm::dvec3 offset) {
  return {[=](glm::dvec3 p) {
            glm::dvec3 placed(roundedToFloat(scale * p + offset));
            return roundedToFloat((placed - offset) / scale);
          },
          1.0};
}

Camera sweepCamera(const Placement& at) {
  Camera camera;
  camera.width = 48;
  camera.height = 36;
  camera.fovYDegrees = 40;
  camera.position = at.point({0.5, 1.0, 6.0});
  camera.forward = glm::normalize(glm::vec3(-0.5f, -1.0f, -6.0f));
  camera.up = {0, 1, 0};
  return camera;
}

Sphere sphereAt(const Placement& at, glm::dvec3 center, double radius) {
  return {at.point(center), float(at.scale * radius)};
}

// A closed mesh (icosphere) with its vertices on the 1/16 grid.
TriangleMesh gridMesh(const Placement& at, glm::dvec3 center) {
  TriangleMesh mesh = icosphere(1);
  for (glm::vec3& p : mesh.positions) {
    glm::dvec3 onGrid = glm::round(glm::dvec3(p) * 16.0) / 16.0;
    p = at.point(onGrid + center);
  }
  return mesh;
}

Quad groundQuad(const Placement& at) {
  return {at.point({-8, -1, 8}), at.point({8, -1, 8}), at.point({8, -1, -8}),
          at.point({-8, -1, -8})};
}

// Matte, mirror and glass spheres, a cylinder, a closed mesh and a ground
// quad under one point light. Unit-scene coordinates are multiples of 1/16,
// so translations below 2^20 - 8 leave them exact.
Scene sweepScene(const Placement& at) {
  Scene scene;
  scene.conventions = Conventions::Textbook;  // no light falloff: brightness is scale free
  scene.camera = sweepCamera(at);
  scene.backgroundColor = {0.1f, 0.2f, 0.3f};
  scene.settings.maxBounces = 3;
  scene.pointLights.push_back({at.point({4, 6, 5}), glm::vec3(1.0f), glm::vec3(1.0f)});
  Material shiny = matte({0.8f, 0.3f, 0.2f});
  shiny.ks = 0.5f;
  shiny.specularExponent = 32;
  Material mirror = matte({0.2f, 0.8f, 0.3f});
  mirror.kd = 0.2f;
  mirror.reflectivity = 0.8f;
  Material glass = matte({0.3f, 0.3f, 0.9f});
  glass.kd = 0.0f;
  glass.transmission = 1.0f;
  glass.ior = 1.5f;
  addShape(scene, sphereAt(at, {0, 0, 0}, 1), shiny);
  addShape(scene, sphereAt(at, {1.75, -0.25, 1}, 0.75), mirror);
  addShape(scene, sphereAt(at, {-1.5, -0.5, 1.5}, 0.5), glass);
  addShape(scene,
           Cylinder{at.point({2.5, 0, -2}), {0, 1, 0}, float(at.scale * 0.5), float(at.scale)},
           matte({0.9f, 0.9f, 0.2f}));
  addMesh(scene, gridMesh(at, {-2.5, 0, -1.5}), matte({0.6f, 0.6f, 0.6f}));
  addShape(scene, groundQuad(at), matte({0.7f, 0.7f, 0.7f}));
  return scene;
}

enum class Layout { Objects, GroundQuad, GroundSphere };

// Self-shadowing probe: the light sits in the camera, so every surface the
// camera sees is lit, and no surface hides part of another in the image
// (a shadow ray leaving within its offset of another object's silhouette
// may legitimately be blocked, so silhouettes over surfaces are avoided).
// The background is pure blue and no material reflects blue.
Scene selfShadowScene(const Placement& at, Layout layout) {
  Scene scene;
  scene.conventions = Conventions::Textbook;
  scene.camera = sweepCamera(at);
  scene.backgroundColor = {0.0f, 0.0f, 1.0f};
  scene.settings.maxBounces = 0;
  scene.pointLights.push_back({scene.camera.position, glm::vec3(1.0f), glm::vec3(1.0f)});
  Material material = matte({0.8f, 0.5f, 0.0f});
  if (layout == Layout::Objects) {
    addShape(scene, sphereAt(at, {0, 0, 0}, 1), material);
    addShape(scene,
             Cylinder{at.point({2.5, 0, -2}), glm::normalize(glm::vec3(1, 2, 0.5f)),
                      float(at.scale * 0.5), float(at.scale)},
             material);
    addMesh(scene, gridMesh(at, {-2.5, 0, -1.5}), material);
  } else if (layout == Layout::GroundQuad) {
    addShape(scene, groundQuad(at), material);
  } else {
    addShape(scene, sphereAt(at, {0, -1001, 0}, 1000), material);
  }
  return scene;
}

std::vector<double> powerOfTwoScales() {
  std::vector<double> scales;
  for (int exponent : {-14, -7, 3, 10, 17, 20}) {
    scales.push_back(std::ldexp(1.0, exponent));
  }
  return scales;
}

// Translations, each a float: exact ones (multiples of 1/16 below 2^20) and
// ones that round the scene (non-dyadic digits, or beyond 2^20).
const std::vector<glm::dvec3> kOffsets = {{1000, 0, 0},
                                          {0, -65536, 0},
                                          {1e6, 1e6, -1e6},
                                          {-999999, 31, 524288},
                                          {123456.7890625, -98765.4296875, 1e6 + 0.5},
                                          {3e6, -2.5e6, 4e6}};

Image8 toImage8(const ImageF& image) {
  Image8 out{image.width, image.height, {}};
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      float v = std::clamp(image.rgba[i + c], 0.0f, 1.0f);
      out.rgb.push_back(uint8_t(std::lround(v * 255.0f)));
    }
  }
  return out;
}

// Pixels that received no light at all although they show a surface, in a
// scene whose background is pure blue and whose materials reflect no blue.
size_t darkSurfacePixels(const ImageF& image) {
  size_t count = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    bool surface = image.rgba[i + 2] == 0.0f;
    count += surface && image.rgba[i] == 0.0f && image.rgba[i + 1] == 0.0f;
  }
  return count;
}

}  // namespace

TEST_SUITE("robustness-sweep") {
  TEST_CASE("power-of-two scales from 2^-14 to 2^20 render the unit scene bit for bit") {
    ImageF unit = render(sweepScene(scaledAndMoved(1, {})));
    REQUIRE(nonFiniteValues(unit) == 0);
    for (double scale : powerOfTwoScales()) {
      CAPTURE(scale);
      ImageF scaled = render(sweepScene(scaledAndMoved(scale, {})));
      CHECK(bitwiseEqual(scaled, unit));
    }
  }

  TEST_CASE("translations up to 1e6, with scaling, render the rounded unit scene bit for bit") {
    for (glm::dvec3 offset : kOffsets) {
      for (double scale : {1.0, 1.0 / 1024}) {
        CAPTURE(offset.x);
        CAPTURE(offset.y);
        CAPTURE(offset.z);
        CAPTURE(scale);
        ImageF moved = render(sweepScene(scaledAndMoved(scale, offset)));
        ImageF reference = render(sweepScene(roundedLike(scale, offset)));
        CAPTURE(pixelsDiffering(moved, reference, 0.0f));
        CHECK(bitwiseEqual(moved, reference));
      }
    }
  }

  TEST_CASE("exact translations change nothing; rounding ones and decimal scales very little") {
    ImageF unit = render(sweepScene(scaledAndMoved(1, {})));
    Image8 unit8 = toImage8(unit);
    for (glm::dvec3 offset : {glm::dvec3(1000, 0, 0), glm::dvec3(0, -65536, 0),
                              glm::dvec3(1e6, 1e6, -1e6), glm::dvec3(-999999, 31, 524288)}) {
      CAPTURE(offset);
      CHECK(bitwiseEqual(render(sweepScene(scaledAndMoved(1, offset))), unit));
    }
    for (double scale : {1e-4, 1e-2, 1e2, 1e4, 1e6}) {
      CAPTURE(scale);
      ImageF scaled = render(sweepScene(scaledAndMoved(scale, {})));
      CHECK(pixelsDiffering(scaled, unit, 1e-3f) <= unit.rgba.size() / 4 / 100);
    }
    ImageF rounded = render(sweepScene(scaledAndMoved(1, {3e6, -2.5e6, 4e6})));
    double decibels = psnr(toImage8(rounded), unit8);
    MESSAGE("unit scene moved by 4e6 (rounded to 1/4): ", decibels, " dB against unmoved");
    CHECK(decibels > 25.0);
  }

  TEST_CASE("no lit pixel is shadowed by its own surface, at any scale or distance") {
    std::vector<Placement> placements;
    for (double scale : {0x1p-14, 0x1p20, 1e-4, 0.1, 1e3, 1e6}) {
      placements.push_back(scaledAndMoved(scale, {}));
    }
    for (glm::dvec3 offset : kOffsets) placements.push_back(scaledAndMoved(1, offset));
    placements.push_back(scaledAndMoved(1, {1e7, -1e7, 1e7}));  // ulp 1: a coarse, odd scene
    placements.push_back(scaledAndMoved(1e-3, {5e3, 0, 0}));
    size_t total = 0, surfacePixels = 0;
    for (Layout layout : {Layout::Objects, Layout::GroundQuad, Layout::GroundSphere}) {
      for (const Placement& at : placements) {
        Scene scene = selfShadowScene(at, layout);
        CAPTURE(int(layout));
        CAPTURE(at.scale);
        ImageF image = render(scene, 1, unguardedCompiler());
        CHECK(nonFiniteValues(image) == 0);
        size_t dark = darkSurfacePixels(image);
        CHECK(dark == 0);
        total += dark;
        for (size_t i = 2; i < image.rgba.size(); i += 4) surfacePixels += image.rgba[i] == 0.0f;
      }
    }
    MESSAGE("self-shadowed pixels: ", total, " of ", surfacePixels, " surface pixels in ",
            3 * placements.size(), " renders");
  }
}
