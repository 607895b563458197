// Tests for rt::loadJsonScene / rt::parseJsonScene: the official and student files
// under shared/scene-format, and hand-written bad inputs that must fail with
// one line naming the file and the JSON path.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formats/json/JsonSceneLoader.hpp"
#include "support/JsonMutations.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

fs::path sceneFormatDir() { return rt::test::requireShared() / "scene-format"; }

std::vector<fs::path> jsonFilesUnder(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool near(glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; }
bool near(const glm::dvec3& a, glm::vec3 b) { return glm::length(a - glm::dvec3(b)) < 1e-5; }

// A small valid family-A scene; each bad-input test breaks one thing in it.
Json minimalScene() {
  return Json::parse(R"({
    "nbounces": 3,
    "camera": {"type": "pinhole", "width": 64, "height": 48, "fov": 45,
               "position": [0, 0, 0], "lookat": [0, 0, 1], "up": [0, 1, 0]},
    "scene": {
      "backgroundcolor": [0, 0, 0],
      "lightsources": [{"type": "pointlight", "position": [0, 1, 0],
                        "is": [1, 1, 1], "id": [2, 2, 2]}],
      "shapes": [{"type": "sphere", "center": [0, 0, 3], "radius": 1,
                  "material": {"ks": 0.1, "kd": 0.9, "specularexponent": 10,
                               "diffusecolor": [1, 0, 0]}}]
    }})");
}

Json& firstShape(Json& scene) { return scene["scene"]["shapes"][0]; }
Json& firstMaterial(Json& scene) { return firstShape(scene)["material"]; }

rt::Scene parse(const Json& document) { return rt::parseJsonScene(document.dump(), "mem.json"); }

// The rt::Error message of parsing `text`, or "" when it loads.
std::string errorOfText(const std::string& text) {
  try {
    rt::parseJsonScene(text, "mem.json");
  } catch (const rt::Error& error) {
    const std::string message = error.what();
    CHECK_MESSAGE(!contains(message, "\n"), "error messages are one line: " << message);
    return message;
  }
  return "";
}

std::string errorOf(const Json& document) { return errorOfText(document.dump()); }

bool hasWarning(const rt::Scene& scene, const std::string& part) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& line) { return contains(line, part); });
}

// Replaces or removes each value of `document` in turn: every variant must
// either load or fail with rt::Error, never with another exception or a crash.
// Returns how many variants were tried.
size_t checkCorruptionsFailCleanly(const Json& document, const fs::path& file = "mem.json") {
  const std::vector<Json> replacements = {
      nullptr, "text", -1, 0, 2.5, 1e30, true, Json::array(), Json::object(), {1, 2, 3}};
  size_t tried = 0;
  rt::test::forEachMutation<Json>(
      document, replacements, [&](const Json::json_pointer& pointer, const Json& variant) {
        ++tried;
        try {
          rt::parseJsonScene(variant.dump(), file);
        } catch (const rt::Error&) {
        } catch (const std::exception& error) {
          FAIL("not an rt::Error at " << pointer.to_string() << ": " << error.what());
        }
      });
  return tried;
}

using rt::test::TempDir;

}  // namespace

TEST_SUITE("scene loader: official files") {
  TEST_CASE("2019 example: camera vectors default to looking down +z from the origin" *
            rt::test::needsShared()) {
    const rt::Scene scene =
        rt::loadJsonScene(sceneFormatDir() / "official/cg-path-of-light-2019/example.json");
    CHECK(scene.conventions == rt::Conventions::CourseworkA);
    CHECK(scene.settings.maxBounces == 3);
    CHECK(scene.camera.type == rt::CameraType::Pinhole);
    CHECK(scene.camera.fovYDegrees == doctest::Approx(35.0));
    CHECK(near(scene.camera.position, {0, 0, 0}));
    CHECK(near(scene.camera.forward, {0, 0, 1}));
    CHECK(near(scene.camera.up, {0, 1, 0}));
    REQUIRE(scene.pointLights.size() == 1);
    CHECK(near(scene.pointLights[0].diffuseIntensity, {1, 1, 1}));
    CHECK(near(scene.pointLights[0].specularIntensity, {1, 1, 1}));
    REQUIRE(scene.shapes.size() == 2);
    const auto& sphere = std::get<rt::Sphere>(scene.shapes[1].geometry);
    CHECK(near(sphere.center, {0.2f, 0.5f, 0.7f}));
    CHECK(scene.materials[scene.shapes[1].material].specularExponent == doctest::Approx(10000));
    // Both spheres lie in front of the default camera.
    for (const rt::Shape& shape : scene.shapes) {
      const auto& s = std::get<rt::Sphere>(shape.geometry);
      CHECK(glm::dot(glm::vec3(s.center - scene.camera.position), scene.camera.forward) > s.radius);
    }
  }

  TEST_CASE("2021-2023 example: lookat is a direction, textures resolve, quads keep v0..v3" *
            rt::test::needsShared()) {
    const rt::Scene scene = rt::loadJsonScene(
        sceneFormatDir() / "official/cg-path-of-light-2021-2023/examples/example.json");
    CHECK(scene.conventions == rt::Conventions::CourseworkA);
    CHECK(scene.shapes.size() == 5);
    REQUIRE(scene.pointLights.size() == 1);
    CHECK(near(scene.pointLights[0].diffuseIntensity, {100, 100, 100}));
    CHECK(near(scene.pointLights[0].specularIntensity, {100, 100, 100}));
    CHECK(near(scene.camera.position, {0.0f, -3.5f, 2.0f}));
    CHECK(near(scene.camera.forward, glm::normalize(glm::vec3(0.0f, 1.0f, -0.1f))));
    CHECK(near(scene.camera.up, {0.0f, 0.0f, 0.5f}));  // kept as given
    CHECK(near(scene.backgroundColor, glm::vec3(0.01f)));

    const rt::Material& sphereMaterial = scene.materials[scene.shapes[0].material];
    CHECK(sphereMaterial.texture.filename() == "sky-map.jpg");
    CHECK(fs::is_regular_file(sphereMaterial.texture));
    REQUIRE(sphereMaterial.diffuseTexture >= 0);
    // The file decides: 852 pixels wide, although tWidth says 850.
    CHECK(scene.textures[sphereMaterial.diffuseTexture].image.width == 852);

    CHECK(scene.shapes[2].label == "floor");
    const auto& floor = std::get<rt::Quad>(scene.shapes[2].geometry);
    CHECK(near(floor.v0, {-2, 8, 0}));
    CHECK(near(floor.v3, {-2, 0, 0}));
    CHECK(scene.materials[scene.shapes[2].material].reflectivity == doctest::Approx(0.3));
    CHECK(std::holds_alternative<rt::Triangle>(scene.shapes[3].geometry));
    CHECK(scene.warnings.empty());  // tWidth/tHeight are accepted silently
  }

  TEST_CASE("family B mirror_image: lookAt is a target, isreflective gates reflectivity" *
            rt::test::needsShared()) {
    const rt::Scene scene =
        rt::loadJsonScene(sceneFormatDir() / "official/cgr-2023-2024/mirror_image.json");
    CHECK(scene.conventions == rt::Conventions::CourseworkB);
    CHECK(scene.settings.mode == rt::RenderMode::Phong);
    CHECK(scene.settings.maxBounces == 8);
    CHECK(scene.camera.exposure == doctest::Approx(0.1));
    CHECK(near(scene.camera.forward, glm::normalize(glm::vec3(1.25f, -0.55f, 2.5f))));
    REQUIRE(scene.shapes.size() == 7);
    const auto& cylinder = std::get<rt::Cylinder>(scene.shapes[2].geometry);
    CHECK(cylinder.halfHeight == doctest::Approx(0.5));
    CHECK(cylinder.radius == doctest::Approx(0.25));
    CHECK(near(cylinder.axis, {0, 1, 0}));
    CHECK(scene.materials[scene.shapes[0].material].reflectivity == 0.0f);
    for (size_t mirror : {5u, 6u}) {
      CHECK(std::holds_alternative<rt::Triangle>(scene.shapes[mirror].geometry));
      CHECK(scene.materials[scene.shapes[mirror].material].reflectivity == 1.0f);
    }
    CHECK(scene.materials[0].transmission == 0.0f);
    CHECK(scene.warnings.empty());
  }

  TEST_CASE("family B binary_primitves: no materials, no lights, default bounces" *
            rt::test::needsShared()) {
    const rt::Scene scene =
        rt::loadJsonScene(sceneFormatDir() / "official/cgr-2023-2024/binary_primitves.json");
    CHECK(scene.conventions == rt::Conventions::CourseworkB);
    CHECK(scene.settings.mode == rt::RenderMode::Binary);
    CHECK(scene.settings.maxBounces == 4);
    CHECK(scene.camera.width == 1200);
    CHECK(scene.camera.height == 800);
    CHECK(scene.pointLights.empty());
    CHECK(scene.shapes.size() == 3);
    CHECK(scene.materials.size() == 3);
    CHECK(scene.warnings.empty());  // binary mode needs no materials
  }

  TEST_CASE("family B scene.json has two lights and six shapes" * rt::test::needsShared()) {
    const rt::Scene scene =
        rt::loadJsonScene(sceneFormatDir() / "official/cgr-2023-2024/scene.json");
    CHECK(scene.settings.mode == rt::RenderMode::Binary);
    CHECK(scene.pointLights.size() == 2);
    CHECK(scene.shapes.size() == 6);
    CHECK(near(scene.pointLights[1].specularIntensity, glm::vec3(0.5f)));
  }

  TEST_CASE("every official file loads without warnings" * rt::test::needsShared()) {
    const std::vector<fs::path> files = jsonFilesUnder(sceneFormatDir() / "official");
    CHECK(files.size() >= 6);
    for (const fs::path& file : files) {
      CAPTURE(file.string());
      rt::Scene scene;
      CHECK_NOTHROW(scene = rt::loadJsonScene(file));
      CHECK(scene.warnings.empty());
      CHECK(!scene.shapes.empty());
      CHECK(scene.materials.size() == scene.shapes.size());
      CHECK(glm::length(scene.camera.forward) == doctest::Approx(1.0));
    }
  }
}

TEST_SUITE("scene loader: robustness") {
  TEST_CASE("corrupting any single value of a scene fails cleanly") {
    Json scene = minimalScene();
    scene["camera"]["type"] = "thinlens";
    scene["camera"]["aperture"] = 0.1;
    scene["camera"]["focusdistance"] = 2;
    scene["scene"]["shapes"].push_back({{"type", "trimesh"},
                                        {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                                        {"faces", {{0, 1, 2}}}});
    scene["scene"]["shapes"].push_back({{"type", "cylinder"},
                                        {"center", {0, 0, 0}},
                                        {"axis", {0, 1, 0}},
                                        {"radius", 1},
                                        {"height", 1},
                                        {"material",
                                         {{"ks", 0.1},
                                          {"kd", 0.9},
                                          {"specularexponent", 20},
                                          {"diffusecolor", {0.5, 0.5, 0.8}},
                                          {"specularcolor", {1, 1, 1}},
                                          {"isreflective", true},
                                          {"reflectivity", 1},
                                          {"isrefractive", false},
                                          {"refractiveindex", 1}}}});
    CHECK(checkCorruptionsFailCleanly(scene) > 500);
  }

  TEST_CASE("corrupting any single value of the textured official file fails cleanly" *
            rt::test::needsShared()) {
    // The file with textures, so the texture lookup is corrupted too.
    const fs::path official =
        sceneFormatDir() / "official/cg-path-of-light-2021-2023/examples/example.json";
    std::ifstream stream(official);
    CHECK(checkCorruptionsFailCleanly(Json::parse(stream), official) > 500);
  }
}

TEST_SUITE("scene loader: student files") {
  TEST_CASE("each student file loads or fails with one rt::Error line" * rt::test::needsShared()) {
    const std::vector<fs::path> files = jsonFilesUnder(sceneFormatDir() / "student");
    size_t loaded = 0;
    for (const fs::path& file : files) {
      CAPTURE(file.string());
      try {
        rt::loadJsonScene(file);
        ++loaded;
      } catch (const rt::Error& error) {
        const std::string message = error.what();
        CHECK(!contains(message, "\n"));
        CHECK(contains(message, file.string() + ": "));
      } catch (const std::exception& error) {
        FAIL("not an rt::Error: " << error.what());
      }
    }
    MESSAGE(loaded << " of " << files.size() << " student scene files load");
  }

  TEST_CASE("known student files: what loads and why the others are rejected" *
            rt::test::needsShared()) {
    const fs::path student = sceneFormatDir() / "student";
    const auto errorOfFile = [&](const char* relative) -> std::string {
      const fs::path file = student / relative;
      if (!fs::exists(file)) return "(absent)";
      try {
        rt::loadJsonScene(file);
      } catch (const rt::Error& error) {
        return error.what();
      }
      return "";
    };
    // Loads (leniently), with a warning that says what was read around.
    const auto expectWarned = [&](const char* relative, const std::string& why) {
      const fs::path file = student / relative;
      if (!fs::exists(file)) return;
      CAPTURE(relative);
      const rt::Scene scene = rt::loadJsonScene(file);
      bool found = false;
      for (const std::string& warning : scene.warnings) found = found || contains(warning, why);
      CHECK(found);
    };
    CHECK(errorOfFile("PeihengLu__CG_CW2/examples/example.json").empty());
    CHECK(errorOfFile("chxag__CGR-Raytracing-CW2/Code/Jsons/complex_one.json").empty());
    CHECK(errorOfFile("julie-o__CG-cw/demo.json").empty());
    // The author did not publish the bear model.
    expectWarned("PeihengLu__CG_CW2/examples/example_trimesh.json",
                 "scene.shapes[5].mPath: mesh file not found: ../ply_models/bear.ply (looked in");
    CHECK(errorOfFile("TsFreddie__RayTracer/examples/monkey_bvh_test.json").empty());
    CHECK(errorOfFile("TsFreddie__RayTracer/examples/dof_test.json").empty());
    CHECK(errorOfFile("TsFreddie__RayTracer/examples/softshadow_test.json").empty());
    // The author's textures are not in the repository.
    expectWarned("PFNK__RayTracer/examples/test.json",
                 "texture file not found: ../textures/map.ppm");
    expectWarned("TsFreddie__RayTracer/input_format.json", "comments (// or /* */) are not JSON");
    CHECK(errorOfFile("nizqleo__RayTracer/examples/triangle.json").empty());  // "Traingle"

    const fs::path thinLens = student / "PeihengLu__CG_CW2/examples/example_thinlens.json";
    if (fs::exists(thinLens)) {
      const rt::Scene scene = rt::loadJsonScene(thinLens);
      CHECK(scene.camera.type == rt::CameraType::ThinLens);
      CHECK(scene.camera.apertureRadius == doctest::Approx(0.1));
      CHECK(scene.camera.focusDistance == doctest::Approx(6.5));
    }
  }
}

TEST_SUITE("scene loader: in-memory scenes") {
  TEST_CASE("a minimal family-A scene") {
    const rt::Scene scene = parse(minimalScene());
    CHECK(scene.conventions == rt::Conventions::CourseworkA);
    CHECK(scene.sourcePath == fs::path("mem.json"));
    CHECK(scene.camera.width == 64);
    CHECK(scene.camera.height == 48);
    CHECK(scene.settings.samplesPerPixel == 0);
    CHECK(scene.settings.mode == rt::RenderMode::Phong);
    REQUIRE(scene.pointLights.size() == 1);
    CHECK(near(scene.pointLights[0].specularIntensity, glm::vec3(1)));
    CHECK(near(scene.pointLights[0].diffuseIntensity, glm::vec3(2)));
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].kd == doctest::Approx(0.9));
    CHECK(scene.materials[0].texture.empty());
    CHECK(scene.warnings.empty());
  }

  TEST_CASE("JSON syntax errors report the byte offset") {
    const std::string error = errorOfText("{\n  \"nbounces\": tru }");
    CHECK(contains(error, "mem.json: byte "));
    CHECK(contains(error, "syntax error"));
    CHECK(!contains(error, "[json.exception"));
    CHECK(contains(errorOfText(""), "mem.json: byte "));
    CHECK(contains(errorOfText("{\"nbounces\": 3, // comment\n}"), "mem.json: byte "));
    const std::string overflow = errorOfText("{\"nbounces\": 1e400}");
    CHECK(contains(overflow, "mem.json: byte 14: "));
    CHECK(contains(overflow, "overflow"));
  }

  TEST_CASE("wrong types name the exact JSON path") {
    Json scene = minimalScene();
    firstMaterial(scene)["kd"] = "0.9";
    CHECK(errorOf(scene) == "mem.json: scene.shapes[0].material.kd: expected a number, got string");

    scene = minimalScene();
    firstMaterial(scene)["diffusecolor"] = {1, 0};
    CHECK(errorOf(scene) ==
          "mem.json: scene.shapes[0].material.diffusecolor: expected an array of 3 numbers, got "
          "an array of 2");

    scene = minimalScene();
    scene["camera"]["position"][1] = nullptr;
    CHECK(errorOf(scene) == "mem.json: camera.position[1]: expected a number, got null");

    scene = minimalScene();
    scene["scene"]["shapes"] = Json::object();
    CHECK(errorOf(scene) == "mem.json: scene.shapes: expected an array, got object");

    CHECK(errorOfText("[1, 2]") == "mem.json: (top level): expected an object, got an array of 2");
  }

  TEST_CASE("missing required keys") {
    Json scene = minimalScene();
    scene = minimalScene();
    scene.erase("camera");
    CHECK(errorOf(scene) == "mem.json: camera: missing required key");
    scene = minimalScene();
    scene["scene"].erase("shapes");
    CHECK(errorOf(scene) == "mem.json: scene.shapes: missing required key");
    scene = minimalScene();
    firstShape(scene).erase("radius");
    CHECK(errorOf(scene) == "mem.json: scene.shapes[0].radius: missing required key");
  }

  TEST_CASE("value ranges") {
    Json scene = minimalScene();
    firstShape(scene)["radius"] = -1;
    CHECK(errorOf(scene) == "mem.json: scene.shapes[0].radius: must be positive, got -1");
    scene = minimalScene();
    firstShape(scene)["radius"] = 1e39;  // finite double, but not a float
    CHECK(contains(errorOf(scene), "scene.shapes[0].radius: number 1e+39 is out of range"));
    scene = minimalScene();
    firstMaterial(scene)["kd"] = -0.5;
    CHECK(errorOf(scene) ==
          "mem.json: scene.shapes[0].material.kd: must not be negative, got -0.5");
    scene = minimalScene();
    firstMaterial(scene)["diffusecolor"][2] = -1;
    CHECK(
        contains(errorOf(scene), "scene.shapes[0].material.diffusecolor[2]: must not be negative"));
    scene = minimalScene();
    firstMaterial(scene)["kr"] = 1.5;
    CHECK(contains(errorOf(scene), "material.kr: must be between 0 and 1, got 1.5"));
    scene = minimalScene();
    scene["scene"]["lightsources"][0]["is"][0] = -1;
    CHECK(contains(errorOf(scene), "scene.lightsources[0].is[0]: must not be negative"));
  }

  TEST_CASE("image size, fov and bounces") {
    Json scene = minimalScene();
    scene["camera"]["width"] = 1e9;
    CHECK(errorOf(scene) == "mem.json: camera.width: must be between 1 and 16384, got 1000000000");
    scene["camera"]["width"] = 1000000000;
    CHECK(errorOf(scene) == "mem.json: camera.width: must be between 1 and 16384, got 1000000000");
    scene["camera"]["width"] = 0;
    CHECK(contains(errorOf(scene), "camera.width: must be between 1 and 16384, got 0"));
    scene["camera"]["width"] = 800.5;
    CHECK(contains(errorOf(scene), "camera.width: expected an integer, got 800.5"));
    scene["camera"]["width"] = 800.0;  // an integral float is still an integer
    CHECK(parse(scene).camera.width == 800);
    scene["camera"]["height"] = 16385;
    CHECK(contains(errorOf(scene), "camera.height: must be between 1 and 16384"));

    scene = minimalScene();
    for (double fov : {0.0, 180.0, -10.0}) {
      scene["camera"]["fov"] = fov;
      CHECK(contains(errorOf(scene), "camera.fov: must be between 0 and 180 degrees"));
    }
    scene["camera"]["fov"] = 179.5;
    CHECK(parse(scene).camera.fovYDegrees == doctest::Approx(179.5));

    scene = minimalScene();
    scene["nbounces"] = -1;
    CHECK(errorOf(scene) == "mem.json: nbounces: must be between 0 and 64, got -1");
    scene["nbounces"] = 65;
    CHECK(contains(errorOf(scene), "nbounces: must be between 0 and 64, got 65"));
    scene["nbounces"] = 0;
    CHECK(parse(scene).settings.maxBounces == 0);
    scene.erase("nbounces");
    CHECK(parse(scene).settings.maxBounces == 4);
  }

  TEST_CASE("camera vectors") {
    Json scene = minimalScene();
    scene["camera"]["lookat"] = {0, 0, 0};
    CHECK(contains(errorOf(scene), "camera.lookat: must be a non-zero, finite vector"));

    scene = minimalScene();
    scene["camera"]["up"] = {0, 0, 0};
    CHECK(contains(errorOf(scene), "camera.up: must be a non-zero, finite vector"));
    scene["camera"]["up"] = {0, 0, 2};
    CHECK(errorOf(scene) == "mem.json: camera.up: is parallel to the view direction");

    scene = minimalScene();
    scene["camera"].erase("up");
    scene["camera"]["lookat"] = {0, -3, 0};
    CHECK(contains(errorOf(scene), "camera.up: missing, and the default up (0, 1, 0) is parallel"));

    scene = minimalScene();
    scene["camera"]["lookat"] = {0, 0, 4};
    scene["camera"]["up"] = {0, 3, 1};  // neither unit nor orthogonal: kept as given
    const rt::Scene loaded = parse(scene);
    CHECK(near(loaded.camera.forward, {0, 0, 1}));
    CHECK(near(loaded.camera.up, {0, 3, 1}));

    scene = minimalScene();
    scene["camera"]["lookAt"] = {1, 1, 1};
    CHECK(contains(errorOf(scene), "camera.lookAt: conflicts with 'camera.lookat'"));

    scene = minimalScene();
    scene["camera"]["upVector"] = {0, 1, 0};
    CHECK(contains(errorOf(scene), "camera.upVector: conflicts with 'camera.up'"));
  }

  TEST_CASE("family B camera: lookAt is a target point") {
    Json scene = minimalScene();
    scene["camera"].erase("lookat");
    scene["camera"].erase("up");
    scene["camera"]["position"] = {1, 2, 3};
    scene["camera"]["lookAt"] = {1, 2, 7};
    scene["camera"]["upVector"] = {0, 1, 0};
    scene["camera"]["exposure"] = 0.25;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.conventions == rt::Conventions::CourseworkB);
    CHECK(near(loaded.camera.forward, {0, 0, 1}));
    CHECK(loaded.camera.exposure == doctest::Approx(0.25));

    scene["camera"]["lookAt"] = {1, 2, 3};
    CHECK(contains(errorOf(scene), "camera.lookAt: target point must differ from the camera"));
    scene["camera"]["lookAt"] = {1, 2, 7};
    scene["camera"]["exposure"] = 0;
    CHECK(contains(errorOf(scene), "camera.exposure: must be positive"));
  }

  TEST_CASE("render mode") {
    Json scene = minimalScene();
    scene["rendermode"] = "raymarch";
    CHECK(errorOf(scene) ==
          "mem.json: rendermode: unknown rendermode 'raymarch' (expected \"binary\", \"phong\" "
          "or \"pathtracer\")");
    scene["rendermode"] = "binary";
    firstShape(scene).erase("material");
    rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.mode == rt::RenderMode::Binary);
    CHECK(loaded.conventions == rt::Conventions::CourseworkB);
    CHECK(loaded.materials.size() == 1);
    CHECK(loaded.warnings.empty());

    scene["rendermode"] = "phong";
    loaded = parse(scene);
    CHECK(hasWarning(loaded, "scene.shapes[0].material: missing; the default material is used"));
  }

  TEST_CASE("lights") {
    Json scene = minimalScene();
    scene["scene"]["lightsources"][0]["type"] = "spotlight";
    CHECK(contains(errorOf(scene), "scene.lightsources[0].type: unknown light type 'spotlight'"));

    scene = minimalScene();
    scene["scene"]["lightsources"][0]["intensity"] = {1, 1, 1};
    CHECK(contains(errorOf(scene), "scene.lightsources[0].is: conflicts with 'intensity'"));

    scene = minimalScene();
    Json& light = scene["scene"]["lightsources"][0];
    light.erase("is");
    light.erase("id");
    CHECK(contains(errorOf(scene), "scene.lightsources[0].intensity: missing"));
    light["id"] = {1, 1, 1};
    CHECK(errorOf(scene) == "mem.json: scene.lightsources[0].is: missing required key");
    light.erase("id");
    light["intensity"] = {0.5, 0.25, 1};
    const rt::Scene loaded = parse(scene);
    CHECK(near(loaded.pointLights[0].diffuseIntensity, {0.5f, 0.25f, 1}));
    CHECK(near(loaded.pointLights[0].specularIntensity, {0.5f, 0.25f, 1}));
    CHECK(loaded.conventions ==
          rt::Conventions::CourseworkA);  // intensity alone is the 2019 format

    scene["scene"].erase("lightsources");
    CHECK(parse(scene).pointLights.empty());
  }

  TEST_CASE("shape types") {
    Json scene = minimalScene();
    firstShape(scene)["type"] = "Blob";
    CHECK(contains(errorOf(scene), "scene.shapes[0].type: unknown shape type 'Blob'"));
    firstShape(scene)["type"] = "ply";
    CHECK(errorOf(scene) ==
          "mem.json: scene.shapes[0].file: missing: a ply shape needs its file (file, path, mPath, "
          "plyPath or filename)");

    scene = minimalScene();
    firstShape(scene) = {{"type", "plane"}, {"v2", {1, 1, 0}}, {"v0", {0, 0, 0}},
                         {"v3", {0, 1, 0}}, {"v1", {1, 0, 0}}, {"id", "floor"}};
    rt::Scene loaded = parse(scene);
    const auto& quad = std::get<rt::Quad>(loaded.shapes[0].geometry);
    CHECK(near(quad.v0, {0, 0, 0}));
    CHECK(near(quad.v1, {1, 0, 0}));
    CHECK(near(quad.v2, {1, 1, 0}));
    CHECK(near(quad.v3, {0, 1, 0}));
    CHECK(loaded.shapes[0].label == "floor");
    CHECK(hasWarning(loaded, "scene.shapes[0].material: missing"));

    firstShape(scene)["id"] = 7;
    CHECK(contains(errorOf(scene), "scene.shapes[0].id: expected a string, got number"));

    firstShape(scene) = {{"type", "triangle"}, {"v0", {0, 0, 0}}, {"v1", {1, 0, 0}}};
    CHECK(errorOf(scene) == "mem.json: scene.shapes[0].v2: missing required key");
  }

  TEST_CASE("cylinders") {
    Json scene = minimalScene();
    firstShape(scene) = {{"type", "cylinder"},
                         {"center", {0, 0, 3}},
                         {"axis", {0, 2, 0}},
                         {"radius", 0.5},
                         {"height", 0.25}};
    const rt::Scene loaded = parse(scene);
    const auto& cylinder = std::get<rt::Cylinder>(loaded.shapes[0].geometry);
    CHECK(near(cylinder.axis, {0, 1, 0}));
    CHECK(cylinder.halfHeight == doctest::Approx(0.25));
    CHECK(loaded.conventions == rt::Conventions::CourseworkA);  // no light uses `intensity`

    firstShape(scene)["axis"] = {0, 0, 0};
    CHECK(contains(errorOf(scene), "scene.shapes[0].axis: must be a non-zero, finite vector"));
    firstShape(scene)["axis"] = {0, 1, 0};
    firstShape(scene)["height"] = 0;
    CHECK(contains(errorOf(scene), "scene.shapes[0].height: must be positive"));
  }

  TEST_CASE("inline triangle meshes") {
    Json scene = minimalScene();
    Json& mesh = firstShape(scene);
    mesh = {{"type", "trimesh"},
            {"vertices", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
            {"faces", {{0, 1, 2, 3}, {0, 2, 3}}}};
    rt::Scene loaded = parse(scene);
    const auto& instance = std::get<rt::MeshInstance>(loaded.shapes[0].geometry);
    REQUIRE(instance.mesh < loaded.meshes.size());
    const rt::TriangleMesh& triangles = loaded.meshes[instance.mesh];
    CHECK(triangles.positions.size() == 4);
    REQUIRE(triangles.faces.size() == 3);  // the quad face becomes a fan of two
    CHECK(triangles.faces[0] == glm::uvec3(0, 1, 2));
    CHECK(triangles.faces[1] == glm::uvec3(0, 2, 3));
    CHECK(triangles.faces[2] == glm::uvec3(0, 2, 3));

    mesh["faces"][1][2] = 4;
    CHECK(errorOf(scene) ==
          "mem.json: scene.shapes[0].faces[1][2]: vertex index 4 is out of range (the mesh has 4 "
          "vertices)");
    mesh["faces"][1][2] = -1;
    CHECK(contains(errorOf(scene), "scene.shapes[0].faces[1][2]: vertex index -1 is out of range"));
    mesh["faces"][1] = {0, 1};
    CHECK(contains(errorOf(scene), "scene.shapes[0].faces[1]: a face needs at least 3"));
    mesh["faces"][1] = {0, 1.5, 2};
    CHECK(contains(errorOf(scene), "scene.shapes[0].faces[1][1]: expected an integer, got 1.5"));
    mesh["faces"][1] = {0, 1, 2};
    mesh["vertices"][3] = {0, 1};
    CHECK(contains(errorOf(scene), "scene.shapes[0].vertices[3]: expected an array of 3 numbers"));
    mesh["vertices"] = Json::array();
    CHECK(contains(errorOf(scene), "scene.shapes[0].vertices: must list at least one vertex"));

    scene = minimalScene();
    firstShape(scene) = {{"type", "trimesh"}, {"plyPath", "../meshes/apple.ply"}};
    const rt::Scene withoutMesh = parse(scene);
    CHECK(withoutMesh.shapes.empty());
    CHECK(
        hasWarning(withoutMesh,
                   "mem.json: scene.shapes[0].plyPath: mesh file not found: ../meshes/apple.ply"));
    CHECK(hasWarning(withoutMesh, "; the shape is left out"));

    scene = minimalScene();
    firstShape(scene) = {{"type", "trimesh"},
                         {"vertices", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}},
                         {"faces", {{0, 1, 2}}},
                         {"sizeScale", 2}};
    loaded = parse(scene);
    CHECK(hasWarning(loaded, "scene.shapes[0].sizeScale: mesh placement 'sizeScale' is only"));
  }

  TEST_CASE("family A material extras: kr, kt, eta and aliases") {
    Json scene = minimalScene();
    firstMaterial(scene)["kr"] = 0.25;
    firstMaterial(scene)["kt"] = 0.75;
    firstMaterial(scene)["eta"] = 1.5;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.materials[0].reflectivity == doctest::Approx(0.25));
    CHECK(loaded.materials[0].transmission == doctest::Approx(0.75));
    CHECK(loaded.materials[0].ior == doctest::Approx(1.5));

    firstMaterial(scene)["ior"] = 1.4;
    CHECK(contains(errorOf(scene),
                   "scene.shapes[0].material.ior: conflicts with 'scene.shapes[0].material.eta'"));
    firstMaterial(scene).erase("ior");
    firstMaterial(scene)["eta"] = 0;
    CHECK(contains(errorOf(scene), "material.eta: must be positive"));
  }

  TEST_CASE("family B material keys") {
    Json scene = minimalScene();
    Json& material = firstMaterial(scene);
    material["specularcolor"] = {0.5, 0.5, 0.5};
    material["isreflective"] = true;
    material["reflectivity"] = 0.6;
    material["isrefractive"] = 1;  // some files write 0/1
    material["refractiveindex"] = 1.33;
    rt::Scene loaded = parse(scene);
    CHECK(near(loaded.materials[0].specularColor, glm::vec3(0.5f)));
    CHECK(loaded.materials[0].reflectivity == doctest::Approx(0.6));
    // Refraction takes what the mirror leaves (weights 0.6 + 0.4).
    CHECK(loaded.materials[0].transmission == doctest::Approx(0.4));
    CHECK(loaded.materials[0].ior == doctest::Approx(1.33));

    material["isreflective"] = 0;
    CHECK(parse(scene).materials[0].reflectivity == 0.0f);
    CHECK(parse(scene).materials[0].transmission == 1.0f);
    material["isreflective"] = "yes";
    CHECK(contains(errorOf(scene),
                   "material.isreflective: expected a boolean (true/false), got string"));
    material["isreflective"] = 2;
    CHECK(contains(errorOf(scene), "material.isreflective: expected a boolean"));

    material.erase("isreflective");
    loaded = parse(scene);
    CHECK(loaded.materials[0].reflectivity == 0.0f);
    CHECK(hasWarning(loaded, "material.reflectivity: ignored"));

    material["kr"] = 0.5;
    CHECK(contains(errorOf(scene), "material.kr: conflicts with 'isreflective'/'reflectivity'"));
    material.erase("kr");
    material["kt"] = 0.5;
    CHECK(contains(errorOf(scene), "material.kt: conflicts with 'isrefractive'"));
  }

  TEST_CASE("textures resolve from the scene folder, then its parent") {
    const TempDir dir;
    const rt::ImageF pixel{1, 1, {0.5f, 0.25f, 1.0f, 1.0f}};
    fs::create_directories(dir.path() / "textures");
    fs::create_directories(dir.path() / "examples");
    rt::writeImage(dir.path() / "textures/a.png", pixel, {});
    rt::writeImage(dir.path() / "examples/b.png", pixel, {});
    dir.write("textures/corrupt.png", "not a png");
    const fs::path sceneFile = dir.path() / "examples/scene.json";

    Json scene = minimalScene();
    firstMaterial(scene)["tPath"] = "../textures/a.png";
    firstMaterial(scene)["tWidth"] = 10;
    firstMaterial(scene)["tHeight"] = 10;
    rt::Scene loaded = rt::parseJsonScene(scene.dump(), sceneFile);
    CHECK(loaded.materials[0].texture == (dir.path() / "textures/a.png").lexically_normal());
    REQUIRE(loaded.materials[0].diffuseTexture == 0);
    REQUIRE(loaded.textures.size() == 1);
    CHECK(loaded.textures[0].image.width == 1);
    CHECK(loaded.textures[0].image.rgba == std::vector<uint8_t>{128, 64, 255, 255});
    CHECK(loaded.warnings.empty());

    firstMaterial(scene).erase("tPath");
    firstMaterial(scene)["texture"] = "examples/b.png";  // only found from the parent folder
    loaded = rt::parseJsonScene(scene.dump(), sceneFile);
    CHECK(loaded.materials[0].texture == (dir.path() / "examples/b.png").lexically_normal());

    firstMaterial(scene)["texture"] = "missing.png";
    loaded = rt::parseJsonScene(scene.dump(), sceneFile);
    REQUIRE(loaded.warnings.size() == 1);
    CHECK(contains(loaded.warnings[0], sceneFile.string() +
                                           ": scene.shapes[0].material.texture: texture file not "
                                           "found: missing.png"));
    CHECK(contains(loaded.warnings[0], "drawn with the missing-texture squares"));
    REQUIRE(loaded.materials[0].diffuseTexture >= 0);
    const rt::ImageRgba8& squares =
        loaded.textures[size_t(loaded.materials[0].diffuseTexture)].image;
    CHECK(std::vector<uint8_t>(squares.rgba.begin(), squares.rgba.begin() + 4) ==
          std::vector<uint8_t>{255, 0, 255, 255});

    firstMaterial(scene)["texture"] = "../textures/corrupt.png";
    try {
      rt::parseJsonScene(scene.dump(), sceneFile);
      FAIL("a corrupt texture must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(), "scene.shapes[0].material.texture: cannot use texture: "));
      CHECK(contains(error.what(), "corrupt.png: cannot read image"));
    }

    firstMaterial(scene)["tPath"] = "b.png";
    CHECK(contains(errorOf(scene), "material.texture: conflicts with"));
  }

  TEST_CASE("thin lens cameras") {
    Json scene = minimalScene();
    Json& camera = scene["camera"];
    camera["type"] = "thinlens";
    camera["aperture"] = 0.2;  // a diameter
    camera["focus_dist"] = 3;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.type == rt::CameraType::ThinLens);
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.1));
    CHECK(loaded.camera.focusDistance == doctest::Approx(3));

    camera["lensRadius"] = 0.1;
    CHECK(contains(errorOf(scene), "camera.lensRadius: conflicts with 'camera.aperture'"));
    camera.erase("aperture");
    camera.erase("focus_dist");
    loaded = parse(scene);  // no focus distance: a pinhole, with a warning
    CHECK(loaded.camera.apertureRadius == 0.0f);
    CHECK(hasWarning(loaded, "camera.focusdistance: missing: a thin lens needs a focus distance"));
    camera["focalDistance"] = 6.5;
    loaded = parse(scene);
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.1));
    CHECK(loaded.camera.focusDistance == doctest::Approx(6.5));

    camera["focusdistance"] = 2;
    CHECK(contains(errorOf(scene), "conflicts with 'camera.focusdistance'"));
  }

  TEST_CASE("thin lens from the seed report's f, d and aperture fraction") {
    Json scene = minimalScene();
    Json& camera = scene["camera"];
    camera["type"] = "thinlens";
    camera["f"] = 3;
    camera["d"] = 6;
    camera["aperture"] = 0.0625;  // f/16
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.focusDistance == doctest::Approx(6.0));  // 1/(1/3 - 1/6)
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.0625 * 3 / 2));

    camera["d"] = 2;
    CHECK(contains(errorOf(scene), "camera.d: must be greater than the focal length f = 3"));
    camera.erase("d");
    const rt::Scene withoutD = parse(scene);  // f without d: a pinhole, with a warning
    CHECK(withoutD.camera.type == rt::CameraType::Pinhole);
    CHECK(hasWarning(withoutD, "camera.d: missing: the focal length 'f' needs"));
    camera["d"] = 6;
    camera["focusdistance"] = 4;
    CHECK(contains(errorOf(scene), "camera.focusdistance: conflicts with 'f' and 'd'"));
  }

  TEST_CASE("a thin lens without an aperture is a pinhole; lens keys on a pinhole warn") {
    Json scene = minimalScene();
    scene["camera"]["type"] = "thinlens";
    rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.type == rt::CameraType::Pinhole);
    CHECK(hasWarning(loaded, "camera.type: thinlens camera without 'aperture'"));

    scene["camera"]["aperture"] = 0;
    loaded = parse(scene);
    CHECK(loaded.camera.type == rt::CameraType::Pinhole);
    CHECK(loaded.warnings.empty());

    scene["camera"]["type"] = "pinhole";
    loaded = parse(scene);
    CHECK(hasWarning(loaded, "camera.aperture: thin lens key 'aperture' ignored"));

    scene["camera"]["type"] = "thinlense";
    CHECK(contains(errorOf(scene), "camera.type: unknown camera type 'thinlense'"));
  }

  TEST_CASE("sampler and sample count at the top level or in the camera") {
    Json scene = minimalScene();
    scene["sampler"] = "random";
    scene["nsamples"] = 16;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Random);
    CHECK(loaded.settings.samplesPerPixel == 16);

    scene = minimalScene();
    scene["camera"]["method"] = "jittering";
    scene["camera"]["spp"] = 4;
    loaded = parse(scene);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Jittered);
    CHECK(loaded.settings.samplesPerPixel == 4);
    CHECK(loaded.warnings.empty());

    scene["samples"] = 4;  // same value in both places is fine
    CHECK(parse(scene).settings.samplesPerPixel == 4);
    scene["samples"] = 8;
    CHECK(contains(errorOf(scene), "camera.spp: conflicts with 'samples'"));
    scene.erase("samples");
    scene["camera"]["spp"] = 0;
    CHECK(contains(errorOf(scene), "camera.spp: must be between 1 and"));
    scene["camera"]["spp"] = 4;
    scene["camera"]["method"] = "stratified";
    CHECK(contains(errorOf(scene), "camera.method: unknown sampler 'stratified'"));

    // Inside `scene` (Seanst98's renderer reads them there): used where the
    // top level and the camera give none.
    scene = minimalScene();
    scene["scene"]["nsamples"] = 4;
    scene["scene"]["sampling"] = "jittering";
    loaded = parse(scene);
    CHECK(loaded.settings.samplesPerPixel == 4);
    CHECK(loaded.settings.samplerGiven);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Jittered);
    scene["spp"] = 2;
    loaded = parse(scene);
    CHECK(loaded.settings.samplesPerPixel == 2);
    CHECK(
        hasWarning(loaded, "scene.nsamples: ignored: the top level or the camera already sets it"));
  }

  TEST_CASE("unknown keys are warnings, renderer settings are silent") {
    Json scene = minimalScene();
    scene["photon_count"] = 30;
    firstMaterial(scene)["anisotropy"] = 0.5;
    scene["bvh"] = true;
    scene["output"] = "out.ppm";
    scene["scene"]["BVH"] = false;
    firstShape(scene)["useBVH"] = true;
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.warnings ==
          std::vector<std::string>{
              "mem.json: scene.shapes[0].material.anisotropy: unknown key 'anisotropy' ignored",
              "mem.json: photon_count: unknown key 'photon_count' ignored"});
  }

  TEST_CASE("family detection") {
    Json scene = minimalScene();
    CHECK(parse(scene).conventions == rt::Conventions::CourseworkA);
    scene["rendermode"] = "phong";
    CHECK(parse(scene).conventions == rt::Conventions::CourseworkB);

    scene = minimalScene();
    scene["camera"]["exposure"] = 1;
    CHECK(parse(scene).conventions == rt::Conventions::CourseworkB);

    scene = minimalScene();
    Json& light = scene["scene"]["lightsources"][0];
    light.erase("is");
    light.erase("id");
    light["intensity"] = {1, 1, 1};
    CHECK(parse(scene).conventions == rt::Conventions::CourseworkA);
    firstMaterial(scene)["specularcolor"] = {1, 1, 1};
    CHECK(parse(scene).conventions == rt::Conventions::CourseworkB);
    firstMaterial(scene)["roughness"] = 0.5;  // TsFreddie's renderer
    CHECK(parse(scene).conventions == rt::Conventions::Textbook);
  }

  TEST_CASE("conventions: a scene key chooses them; the reason is kept; image right follows") {
    Json scene = minimalScene();
    rt::Scene detected = parse(scene);
    CHECK(detected.conventionsReason == "no family B key (family A, Path of Light)");
    CHECK(detected.camera.imageRight == rt::ImageRight::ForwardCrossUp);
    scene["rendermode"] = "phong";
    detected = parse(scene);
    CHECK(detected.conventionsReason == "family B key 'rendermode'");
    CHECK(detected.camera.imageRight == rt::ImageRight::UpCrossForward);
    scene["conventions"] = "textbook";
    const rt::Scene chosen = parse(scene);
    CHECK(chosen.conventions == rt::Conventions::Textbook);
    CHECK(chosen.conventionsReason == "the scene's 'conventions' key");
    CHECK(chosen.camera.imageRight == rt::ImageRight::ForwardCrossUp);
    CHECK(chosen.warnings.empty());
    scene["conventions"] = "coursework-c";
    CHECK(errorOf(scene) ==
          "mem.json: conventions: unknown conventions 'coursework-c' (expected "
          "\"coursework-a\", \"coursework-b\", \"textbook\" or \"physical\")");
    scene["conventions"] = 2;
    CHECK(errorOf(scene) == "mem.json: conventions: expected a string, got number");
  }

  TEST_CASE("loadJsonScene reads files and reports unreadable ones") {
    const TempDir dir;
    const fs::path file = dir.write("scene.json", minimalScene().dump());
    const rt::Scene scene = rt::loadJsonScene(file);
    CHECK(scene.sourcePath == file);
    CHECK(scene.shapes.size() == 1);

    const fs::path missing = dir.path() / "nope.json";
    try {
      rt::loadJsonScene(missing);
      FAIL("a missing file must fail");
    } catch (const rt::Error& error) {
      CHECK(std::string(error.what()) ==
            missing.string() + ": cannot open: No such file or directory");
    }
    try {
      rt::loadJsonScene(dir.path());
      FAIL("a folder must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(), ": cannot open: Is a directory"));
    }
    const fs::path broken = dir.write("broken.json", "{\"camera\": ");
    try {
      rt::loadJsonScene(broken);
      FAIL("broken JSON must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(), broken.string() + ": byte "));
    }
  }
}

namespace {

// One right triangle with smooth normals, in ASCII PLY.
const std::string kTrianglePly =
    "ply\nformat ascii 1.0\nelement vertex 3\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float nx\nproperty float ny\nproperty float nz\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";

Json plyShape(const std::string& type, const std::string& key, const std::string& file) {
  return {{"type", type},
          {key, file},
          {"material",
           {{"ks", 0.1}, {"kd", 0.9}, {"specularexponent", 10}, {"diffusecolor", {1, 1, 1}}}}};
}

const rt::MeshInstance& instanceOf(const rt::Scene& scene, size_t shape) {
  return std::get<rt::MeshInstance>(scene.shapes.at(shape).geometry);
}

glm::vec3 placed(const rt::MeshInstance& instance, glm::vec3 point) {
  return glm::vec3(instance.objectToWorld * glm::dvec4(glm::dvec3(point), 1.0));
}

// A student scene with its (unpublished) textures dropped, read as if from its own folder.
rt::Scene loadWithoutTextures(const fs::path& file) {
  Json document = Json::parse(std::ifstream(file));
  for (Json& shape : document["scene"]["shapes"]) {
    if (!shape.contains("material")) continue;
    for (const char* key : {"tPath", "tWidth", "tHeight"}) shape["material"].erase(key);
  }
  return rt::parseJsonScene(document.dump(), file);
}

}  // namespace

TEST_SUITE("scene loader: area lights and render modes") {
  Json areaLight(Json geometry) {
    Json light = {{"type", "arealight"}, {"is", {10, 10, 10}}, {"id", {20, 20, 20}}};
    light.update(geometry);
    return light;
  }

  TEST_CASE("every geometric form becomes an emitting shape") {
    Json scene = minimalScene();
    Json& lights = scene["scene"]["lightsources"];
    lights.push_back(areaLight({{"v0", {0, 2, 0}},
                                {"v1", {1, 2, 0}},
                                {"v2", {1, 2, 1}},
                                {"v3", {0, 2, 1}},
                                {"samples", 9},
                                {"method", "jittered"}}));
    lights.push_back(areaLight({{"v0", {0, 2, 0}}, {"v1", {1, 2, 0}}, {"v2", {1, 2, 1}}}));
    lights.push_back(areaLight({{"position", {0, 3, 0}}, {"u", {2, 0, 0}}, {"v", {0, 0, 1}}}));
    lights.push_back(areaLight({{"position", {0, 3, 0}},
                                {"u", {3, 0, 0}},
                                {"v", {0, 0, 1}},
                                {"width", 0.5},
                                {"height", 4}}));
    lights.push_back(areaLight({{"position", {0, 4, 0}}, {"radius", 0.25}}));
    lights.push_back(areaLight({{"position", {0, 4, 0}}, {"size", 0.1}, {"nsamples", 4}}));
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.warnings.empty());
    REQUIRE(loaded.pointLights.size() == 1);
    REQUIRE(loaded.areaLights.size() == 6);
    REQUIRE(loaded.shapes.size() == 7);
    CHECK(loaded.areaLights[0].samples == 9);
    CHECK(loaded.areaLights[5].samples == 4);
    CHECK(loaded.areaLights[1].samples == 1);
    CHECK(near(loaded.areaLights[0].specularIntensity, glm::vec3(10)));
    CHECK(near(loaded.areaLights[0].diffuseIntensity, glm::vec3(20)));
    for (size_t i = 0; i < loaded.areaLights.size(); ++i) {
      CHECK(loaded.areaLights[i].shape == i + 1);
      const rt::Material& material = loaded.materials[loaded.shapes[i + 1].material];
      CHECK(material.kd == 0.0f);  // the light's own surface only emits
      CHECK(material.ks == 0.0f);
    }
    CHECK(std::holds_alternative<rt::Quad>(loaded.shapes[1].geometry));
    CHECK(std::holds_alternative<rt::Triangle>(loaded.shapes[2].geometry));
    const auto& centred = std::get<rt::Quad>(loaded.shapes[3].geometry);
    CHECK(near(centred.v0, {-1, 3, -0.5f}));
    CHECK(near(centred.v2, {1, 3, 0.5f}));
    const auto& sized = std::get<rt::Quad>(loaded.shapes[4].geometry);
    CHECK(near(sized.v2 - sized.v0, {0.5f, 0, 4}));
    CHECK(std::get<rt::Sphere>(loaded.shapes[5].geometry).radius == doctest::Approx(0.25));
    CHECK(std::get<rt::Sphere>(loaded.shapes[6].geometry).radius == doctest::Approx(0.05));
    // The light asked for jittered sampling and the file names no sampler.
    CHECK(loaded.settings.sampler == rt::SamplerKind::Jittered);
  }

  TEST_CASE("a light may name a shape by its id") {
    Json scene = minimalScene();
    firstShape(scene)["id"] = "lamp";
    scene["scene"]["lightsources"].push_back(areaLight({{"shape", "lamp"}, {"samples", 2}}));
    rt::Scene loaded = parse(scene);
    REQUIRE(loaded.areaLights.size() == 1);
    CHECK(loaded.areaLights[0].shape == 0);
    CHECK(loaded.shapes.size() == 1);

    scene["scene"]["lightsources"][1]["shape"] = "missing";
    CHECK(errorOf(scene) == "mem.json: scene.lightsources[1].shape: no shape has the id 'missing'");
    scene["scene"]["lightsources"][1]["shape"] = "lamp";
    scene["scene"]["lightsources"].push_back(areaLight({{"shapeId", "lamp"}}));
    CHECK(errorOf(scene) ==
          "mem.json: scene.lightsources[2].shapeId: shape 'lamp' already is a light");
  }

  TEST_CASE("bad area lights name the key") {
    Json scene = minimalScene();
    scene["scene"]["lightsources"].push_back(areaLight({{"v0", {0, 2, 0}}, {"v1", {1, 2, 0}}}));
    CHECK(errorOf(scene) == "mem.json: scene.lightsources[1].v2: missing required key");
    scene["scene"]["lightsources"][1] = areaLight({{"center", {0, 2, 0}}});
    CHECK(contains(errorOf(scene), "scene.lightsources[1].position: missing required key"));
    scene["scene"]["lightsources"][1] = areaLight({{"position", {0, 2, 0}}});
    const rt::Scene positionOnly = parse(scene);  // read as a point light, with a warning
    CHECK(positionOnly.areaLights.empty());
    CHECK(positionOnly.pointLights.size() == 2);
    CHECK(hasWarning(positionOnly, "an area light without a surface (position only)"));
    scene["scene"]["lightsources"][1] = areaLight({{"position", {0, 2, 0}}, {"u", {1, 0, 0}}});
    CHECK(contains(errorOf(scene), "scene.lightsources[1].v: missing required key"));
    scene["scene"]["lightsources"][1] = areaLight({{"position", {0, 2, 0}}, {"radius", -1}});
    CHECK(contains(errorOf(scene), "scene.lightsources[1].radius:"));
    scene["scene"]["lightsources"][1] =
        areaLight({{"position", {0, 2, 0}}, {"radius", 1}, {"samples", 0}});
    CHECK(contains(errorOf(scene), "scene.lightsources[1].samples:"));
    scene["scene"]["lightsources"][1] =
        areaLight({{"position", {0, 2, 0}}, {"radius", 1}, {"samples", 1e9}});
    CHECK(contains(errorOf(scene), "scene.lightsources[1].samples:"));
    scene["scene"]["lightsources"][1] = {
        {"type", "arealight"}, {"radius", 1}, {"position", {0, 0, 0}}};
    CHECK(contains(errorOf(scene), "scene.lightsources[1].intensity: missing"));
  }

  TEST_CASE("render modes and the mixed mode's two depths") {
    Json scene = minimalScene();
    scene["rendermode"] = "pathtracer";
    CHECK(parse(scene).settings.mode == rt::RenderMode::PathTracer);
    scene["rendermode"] = "raymarching";
    CHECK(contains(errorOf(scene), "rendermode: unknown rendermode 'raymarching'"));
    scene["rendermode"] = "phong";
    scene["distributedbounces"] = 2;
    CHECK(parse(scene).settings.distributedBounces == 2);
    scene["distributedbounces"] = 65;
    CHECK(contains(errorOf(scene), "distributedbounces:"));
    scene["distributedbounces"] = 1;
    scene["rendermode"] = "pathtracer";
    CHECK(hasWarning(parse(scene), "distributedbounces: ignored"));
  }

  TEST_CASE("the firefly clamp: off unless given, a non-negative number") {
    Json scene = minimalScene();
    CHECK(parse(scene).settings.indirectClamp == 0.0f);
    scene["clampindirect"] = 2.5;
    CHECK(parse(scene).settings.indirectClamp == 2.5f);
    scene["clampindirect"] = -1;
    CHECK(contains(errorOf(scene), "clampindirect:"));
    scene["clampindirect"] = "high";
    CHECK(contains(errorOf(scene), "clampindirect:"));
    scene.erase("clampindirect");
    scene["clamp_indirect"] = 0;
    CHECK(parse(scene).settings.indirectClamp == 0.0f);
  }

  TEST_CASE("TsFreddie's forms: vertices arrays, thinlen, tris and uv, checkerboard") {
    Json scene = minimalScene();
    scene["scene"]["lightsources"][0] = {
        {"type", "pointlight"}, {"position", {0, 1, 0}}, {"intensity", {1, 1, 1}}};
    scene["camera"]["type"] = "thinlen";
    scene["camera"]["size"] = 0.2;
    scene["camera"]["focusdistance"] = 2;
    scene["scene"]["shapes"].push_back({{"type", "plane"},
                                        {"vertices", {{0, 0, 0}, {2, 0, 0}, {0, 0, 3}}},
                                        {"material",
                                         {{"ks", 0},
                                          {"kd", 1},
                                          {"specularexponent", 1},
                                          {"diffusecolor", {1, 1, 1}},
                                          {"diffuse", "checkerboard"},
                                          {"transmit", 0.5},
                                          {"metallic", 0.25}}}});
    scene["scene"]["shapes"].push_back(
        {{"type", "trimesh"},
         {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
         {"tris", {{0, 1, 2}}},
         {"uv", {{0, 0}, {1, 0}, {0, 1}}},
         {"material",
          {{"ks", 0}, {"kd", 1}, {"specularexponent", 1}, {"diffusecolor", {1, 1, 1}}}}});
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.type == rt::CameraType::ThinLens);
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.1));
    const auto& quad = std::get<rt::Quad>(loaded.shapes[1].geometry);
    CHECK(near(quad.v2, {2, 0, 3}));  // the parallelogram's fourth corner
    CHECK(near(quad.v3, {0, 0, 3}));
    const rt::Material& material = loaded.materials[loaded.shapes[1].material];
    CHECK(material.transmission == doctest::Approx(0.5));
    CHECK(material.reflectivity == doctest::Approx(0.25));
    REQUIRE(material.diffuseTexture >= 0);
    CHECK(loaded.textures[material.diffuseTexture].image.width == 64);
    REQUIRE(loaded.meshes.size() == 1);
    CHECK(loaded.meshes[0].uvs.size() == 3);
    CHECK(loaded.conventions == rt::Conventions::Textbook);  // TsFreddie's conventions

    scene["scene"]["shapes"][1]["vertices"] = {{0, 0, 0}, {2, 0, 0}};
    CHECK(contains(errorOf(scene), "scene.shapes[1].vertices: expected 3 or 4 vertices, got 2"));
  }

  TEST_CASE("a camera without a view direction looks towards the shapes along z") {
    Json scene = minimalScene();
    scene["camera"].erase("lookat");
    CHECK(near(parse(scene).camera.forward, {0, 0, 1}));
    firstShape(scene)["center"] = {0, 0, -3};
    scene["scene"]["shapes"].push_back({{"type", "plane"},
                                        {"v0", {-9, -1, 9}},
                                        {"v1", {9, -1, 9}},
                                        {"v2", {9, -1, 30}},
                                        {"v3", {-9, -1, 30}},
                                        {"material", firstMaterial(scene)}});
    CHECK(near(parse(scene).camera.forward, {0, 0, -1}));  // the floor behind does not count
  }
}

TEST_SUITE("scene loader: PLY meshes") {
  TEST_CASE("a trimesh names its PLY file under any alias; placement is translate * scale") {
    const TempDir dir;
    dir.write("meshes/tri.ply", kTrianglePly);
    const fs::path sceneFile = dir.path() / "examples/scene.json";
    for (const char* key : {"mPath", "plyPath", "file", "path"}) {
      CAPTURE(key);
      Json scene = minimalScene();
      firstShape(scene) = plyShape("trimesh", key, "../meshes/tri.ply");
      firstShape(scene)["center"] = {1, 2, 3};
      firstShape(scene)["scale"] = 2;
      const rt::Scene loaded = rt::parseJsonScene(scene.dump(), sceneFile);
      const rt::MeshInstance& instance = instanceOf(loaded, 0);
      REQUIRE(loaded.meshes.size() == 1);
      const rt::TriangleMesh& mesh = loaded.meshes[instance.mesh];
      CHECK(mesh.positions.size() == 3);
      CHECK(mesh.faces.size() == 1);
      CHECK(mesh.normals == std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)));  // smooth shading
      CHECK(near(placed(instance, {0, 0, 0}), {1, 2, 3}));
      CHECK(near(placed(instance, {1, 0, 0}), {3, 2, 3}));
      CHECK(loaded.warnings.empty());
    }
    Json scene = minimalScene();
    firstShape(scene) = plyShape("trimesh", "mPath", "../meshes/tri.ply");
    CHECK(near(placed(instanceOf(rt::parseJsonScene(scene.dump(), sceneFile), 0), {1, 1, 1}),
               {1, 1, 1}));  // no placement: the file's own coordinates
    firstShape(scene)["pos"] = {0, -1, 0};
    firstShape(scene)["sizeScale"] = 0.5;
    CHECK(near(placed(instanceOf(rt::parseJsonScene(scene.dump(), sceneFile), 0), {0, 1, 0}),
               {0, -0.5f, 0}));
    firstShape(scene)["scale"] = 2;
    CHECK(contains(errorOf(scene), "scene.shapes[0]"));
    firstShape(scene).erase("scale");
    firstShape(scene)["sizeScale"] = 0;
    try {
      rt::parseJsonScene(scene.dump(), sceneFile);
      FAIL("a zero scale must fail");
    } catch (const rt::Error& error) {
      CHECK(contains(error.what(), "scene.shapes[0].sizeScale: must be positive"));
    }
  }

  TEST_CASE("type ply; paths from the scene folder or its parent; shapes share one mesh") {
    const TempDir dir;
    dir.write("examples/meshes/tri.ply", kTrianglePly);
    const fs::path sceneFile = dir.path() / "examples/scene.json";
    Json scene = minimalScene();
    scene["scene"]["shapes"] = {plyShape("ply", "file", "examples/meshes/tri.ply"),
                                plyShape("trimesh", "mPath", "meshes/tri.ply"),
                                plyShape("trimesh", "plyPath", "../examples/meshes/tri.ply")};
    scene["scene"]["shapes"][2]["center"] = {0, 0, 5};
    const rt::Scene loaded = rt::parseJsonScene(scene.dump(), sceneFile);
    CHECK(loaded.meshes.size() == 1);
    REQUIRE(loaded.shapes.size() == 3);
    for (size_t i = 0; i < 3; ++i) CHECK(instanceOf(loaded, i).mesh == 0);
    CHECK(near(placed(instanceOf(loaded, 2), {0, 0, 0}), {0, 0, 5}));
    CHECK(loaded.warnings.empty());
  }

  TEST_CASE("PLY errors keep their byte offset and gain the JSON path") {
    const TempDir dir;
    std::string bad = kTrianglePly;
    bad.replace(bad.find("3 0 1 2"), 7, "3 0 1 7");
    const fs::path badFile = dir.write("meshes/bad.ply", bad);
    const fs::path sceneFile = dir.path() / "examples/scene.json";
    Json scene = minimalScene();
    scene["scene"]["shapes"][1] = plyShape("trimesh", "mPath", "../meshes/bad.ply");
    const auto errorIn = [&](const Json& document) -> std::string {
      try {
        rt::parseJsonScene(document.dump(), sceneFile);
      } catch (const rt::Error& error) {
        return error.what();
      }
      return "";
    };
    CHECK(errorIn(scene) == sceneFile.string() +
                                ": scene.shapes[1].mPath: " + badFile.lexically_normal().string() +
                                ": byte " + std::to_string(bad.find("7\n")) +
                                ": face 0: vertex index 7 is out of range (the file has 3 "
                                "vertices)");
    scene["scene"]["shapes"][1]["mPath"] = "../meshes/none.ply";
    const rt::Scene withoutMesh = rt::parseJsonScene(scene.dump(), sceneFile);
    CHECK(withoutMesh.shapes.size() == 1);
    CHECK(contains(withoutMesh.warnings.at(0),
                   "scene.shapes[1].mPath: mesh file not found: ../meshes/none.ply (looked in"));
    scene["scene"]["shapes"][1]["mPath"] = "";
    CHECK(contains(errorIn(scene), "scene.shapes[1].mPath: must not be an empty string"));
    scene["scene"]["shapes"][1]["mPath"] = "../meshes/bad.ply";
    scene["scene"]["shapes"][1]["vertices"] = {{0, 0, 0}};
    CHECK(contains(errorIn(scene),
                   "scene.shapes[1].vertices: conflicts with 'scene.shapes[1].mPath': give inline "
                   "vertices or a mesh file"));
    scene["scene"]["shapes"][1] = plyShape("trimesh", "mPath", "../meshes/bad.ply");
    scene["scene"]["shapes"][1]["file"] = "../meshes/bad.ply";
    CHECK(contains(errorIn(scene), "scene.shapes[1].file: conflicts with"));
  }

  TEST_CASE("student scenes with PLY meshes" * rt::test::needsShared()) {
    const fs::path student = sceneFormatDir() / "student";
    const fs::path monkeyScene = student / "TsFreddie__RayTracer/examples/monkey_bvh_test.json";
    if (fs::exists(monkeyScene)) {
      const rt::Scene monkey = rt::loadJsonScene(monkeyScene);
      REQUIRE(monkey.meshes.size() == 1);
      CHECK(monkey.meshes[0].positions.size() == 2874);
      CHECK(monkey.meshes[0].faces.size() == 968);
      CHECK(monkey.meshes[0].normals.size() == 2874);
      CHECK(monkey.meshes[0].uvs.size() == 2874);
      CHECK(instanceOf(monkey, 0).objectToWorld == rt::WorldTransform(1.0));
    }
    // PFNK's scenes also use textures that were never published.
    const fs::path pfnk = student / "PFNK__RayTracer/examples/exampleMesh.json";
    if (fs::exists(pfnk)) {
      const rt::Scene octahedron = loadWithoutTextures(pfnk);
      REQUIRE(octahedron.meshes.size() == 1);
      CHECK(octahedron.meshes[0].positions.size() == 6);
      CHECK(octahedron.meshes[0].faces.size() == 8);
      const rt::MeshInstance& instance = instanceOf(octahedron, octahedron.shapes.size() - 1);
      CHECK(near(placed(instance, {0, 0, 0}), {0.0f, 2.7f, 1.15f}));
      CHECK(near(placed(instance, {1, 0, 0}), {0.2f, 2.7f, 1.15f}));
    }
    const fs::path beethoven = student / "PFNK__RayTracer/examples/example.json";
    if (fs::exists(beethoven))
      CHECK(loadWithoutTextures(beethoven).meshes.at(0).faces.size() == 5030);
  }
}
