// One scene rendered at many scales and distances from the world origin.
//
// The model keeps world positions in double precision and the GPU encoding
// subtracts the camera's position before rounding to float
// (src/encode/GpuFrame.hpp), and every tolerance of the shaders is relative
// (ray offsets in shaders/geometry.glsl). So:
// - scaling by a power of two is exact all the way: the same image bit for
//   bit (sweep 2^-14 to 2^20);
// - a translation that double precision holds exactly (the unit scene's
//   coordinates are multiples of 1/16) changes nothing either, up to 1e9;
// - decimal scales (1e-4 to 1e6) and decimal offsets (up to 1e9) round the
//   scene's coordinates by about 1e-16 of their size in double, and the
//   camera-relative floats by 6e-8 of the scene's size: the image stays
//   within 60 dB (8-bit PSNR) of the unit scene;
// - only a scene so small and so far away that double precision cannot
//   place it (precisionProblem, scene/SceneBounds.hpp) is refused, with a
//   message.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "encode/FlatScene.hpp"
#include "formats/common/FileBytes.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "robustness/RobustnessSupport.hpp"
#include "scene/SceneBounds.hpp"
#include "util/Error.hpp"

using namespace rt;
using namespace rt::test;

namespace {

// Where a unit-scene point goes, and how lengths scale.
struct Placement {
  std::function<WorldPoint(glm::dvec3)> point;
  double scale = 1.0;
};

Placement scaledAndMoved(double scale, glm::dvec3 offset) {
  return {[=](glm::dvec3 p) { return scale * p + offset; }, scale};
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

// A closed mesh (icosphere) with its vertices on the 1/16 grid, in its own
// space, and where it is placed.
struct PlacedMesh {
  TriangleMesh mesh;
  WorldTransform objectToWorld;
};

PlacedMesh gridMesh(const Placement& at, glm::dvec3 center) {
  TriangleMesh mesh = icosphere(1);
  for (glm::vec3& p : mesh.positions) p = glm::vec3(glm::round(glm::dvec3(p) * 16.0) / 16.0);
  WorldTransform placement = glm::translate(WorldTransform(1.0), at.point(center));
  return {mesh, glm::scale(placement, glm::dvec3(at.scale))};
}

void addPlacedMesh(Scene& scene, PlacedMesh placed, const Material& material) {
  scene.meshes.push_back(std::move(placed.mesh));
  addShape(scene, MeshInstance{uint32_t(scene.meshes.size() - 1), placed.objectToWorld}, material);
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
  addPlacedMesh(scene, gridMesh(at, {-2.5, 0, -1.5}), matte({0.6f, 0.6f, 0.6f}));
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
    addPlacedMesh(scene, gridMesh(at, {-2.5, 0, -1.5}), material);
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

// Translations that double precision holds exactly with the unit scene
// added (dyadic, below 2^53 with the scene's 2^-14 steps), up to 1e9.
const std::vector<glm::dvec3> kExactOffsets = {{1000, 0, 0},
                                               {0, -65536, 0},
                                               {1e6, 1e6, -1e6},
                                               {-999999, 31, 524288},
                                               {123456.7890625, -98765.4296875, 1e6 + 0.5},
                                               {1e9, -0x1p29, 7e8}};

// Decimal ones, which round the placed scene (in double).
const std::vector<glm::dvec3> kDecimalOffsets = {{0, 0, 0},
                                                 {123456.789, -98765.4321, 1e6 + 0.3},
                                                 {3.3e6, -2.5e6, 4.1e6},
                                                 {1e9 + 0.1, -3e8, 7e8}};

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

// A scene file's geometry scaled about the world origin and moved, as its
// author would write it there: positions, corners and vertices become
// s p + T, radii and heights s r (a family-B file: no light falloff).
void placeJson(nlohmann::json& node, double scale, glm::dvec3 offset) {
  const auto place = [&](nlohmann::json& point) {
    for (int i = 0; i < 3; ++i) point[i] = scale * point[i].get<double>() + offset[i];
  };
  if (!node.is_object() && !node.is_array()) return;
  for (auto item = node.begin(); item != node.end(); ++item) {
    const std::string key = node.is_object() ? item.key() : "";
    if (key == "camera") {
      place((*item)["position"]);
      place((*item)["lookAt"]);
    } else if (key == "position" || key == "lookAt" || key == "center" || key == "v0" ||
               key == "v1" || key == "v2" || key == "v3") {
      place(*item);
    } else if (key == "vertices") {
      for (nlohmann::json& vertex : *item) place(vertex);
    } else if (key == "radius" || key == "height") {
      *item = scale * item->get<double>();
    } else {
      placeJson(*item, scale, offset);
    }
  }
}

Scene defaultSceneAt(double scale, glm::dvec3 offset) {
  nlohmann::json document =
      nlohmann::json::parse(readFileOrThrow(projectScenePath("default.json")));
  placeJson(document, scale, offset);
  Scene scene = parseJsonScene(document.dump(), "placed-default.json");
  scene.camera.width = 80;
  scene.camera.height = 60;
  return scene;
}

// Renders `sceneAt(scale, offset)` at each scale and decimal offset: each
// image must be within 60 dB of the unit scene's, or the scene refused as
// precisionProblem says, with a message. Returns a table of the results.
std::string sweepDecimal(std::initializer_list<double> scales,
                         const std::function<Scene(double, glm::dvec3)>& sceneAt) {
  const Image8 unit = toImage8(render(sceneAt(1.0, {})));
  std::string table;
  for (double scale : scales) {
    for (glm::dvec3 offset : kDecimalOffsets) {
      CAPTURE(scale);
      CAPTURE(offset);
      Scene scene = sceneAt(scale, offset);
      std::string row = fmt::format("  scale {:g} offset {:g}: ", scale, offset.x);
      if (const std::optional<std::string> problem = precisionProblem(scene)) {
        table += row + "refused (" + *problem + ")\n";
        CHECK_THROWS_WITH_AS(render(scene), doctest::Contains(": the shapes are"), Error);
        continue;
      }
      Image8 image = toImage8(render(scene));
      double decibels = image.rgb == unit.rgb ? INFINITY : psnr(image, unit);
      table += row + fmt::format("{:.1f} dB\n", decibels);
      CHECK(decibels > 60.0);
    }
  }
  return table;
}

}  // namespace

TEST_SUITE("robustness-sweep") {
  TEST_CASE("scenes/default.json written at scales 1e-4 to 1e6 and up to 1e9 away renders alike") {
    std::string table = sweepDecimal({1e-4, 1e-2, 1e2, 1e6}, defaultSceneAt);
    MESSAGE("default.json, 8-bit PSNR against itself unmoved:\n", table);
  }

  TEST_CASE("power-of-two scales from 2^-14 to 2^20 render the unit scene bit for bit") {
    ImageF unit = render(sweepScene(scaledAndMoved(1, {})));
    REQUIRE(nonFiniteValues(unit) == 0);
    for (double scale : powerOfTwoScales()) {
      CAPTURE(scale);
      ImageF scaled = render(sweepScene(scaledAndMoved(scale, {})));
      CHECK(bitwiseEqual(scaled, unit));
    }
  }

  TEST_CASE("exact translations up to 1e9, with scaling, render the unmoved scene bit for bit") {
    for (double scale : {1.0, 1.0 / 1024}) {
      ImageF unmoved = render(sweepScene(scaledAndMoved(scale, {})));
      for (glm::dvec3 offset : kExactOffsets) {
        CAPTURE(offset);
        CAPTURE(scale);
        Scene scene = sweepScene(scaledAndMoved(scale, offset));
        if (precisionProblem(scene)) {  // 2^-10 at 1e9: the scene is 0.02 across
          CHECK(scale < 1.0);
          continue;
        }
        ImageF moved = render(scene);
        CAPTURE(pixelsDiffering(moved, unmoved, 0.0f));
        CHECK(bitwiseEqual(moved, unmoved));
      }
    }
  }

  TEST_CASE(
      "decimal scales 1e-4 to 1e6 and offsets up to 1e9 stay within 60 dB of the unit scene") {
    std::string table = sweepDecimal(
        {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6},
        [](double scale, glm::dvec3 offset) { return sweepScene(scaledAndMoved(scale, offset)); });
    MESSAGE("8-bit PSNR against the unit scene:\n", table);
  }

  TEST_CASE("no lit pixel is shadowed by its own surface, at any scale or distance") {
    std::vector<Placement> placements;
    for (double scale : {0x1p-14, 0x1p20, 1e-4, 0.1, 1e3, 1e6}) {
      placements.push_back(scaledAndMoved(scale, {}));
    }
    for (glm::dvec3 offset : kExactOffsets) placements.push_back(scaledAndMoved(1, offset));
    for (glm::dvec3 offset : kDecimalOffsets) placements.push_back(scaledAndMoved(0.1, offset));
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
