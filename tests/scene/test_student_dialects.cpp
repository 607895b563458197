// Students' other spellings of what the renderer knows (README "Student
// scenes"), lenient loading (defaults taken and missing files, each with a
// warning) and --strict, on small scenes written for each dialect.
#include <doctest/doctest.h>

#include <filesystem>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "encode/Conventions.hpp"
#include "formats/SceneFile.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

namespace {

using Json = nlohmann::ordered_json;

Json baseScene() {
  return Json::parse(R"({
    "camera": {"type": "pinhole", "width": 32, "height": 24, "fov": 45,
               "position": [0, 0, 0], "lookat": [0, 0, 1], "up": [0, 1, 0]},
    "scene": {"lightsources": [{"type": "pointlight", "position": [0, 5, 0], "is": [1, 1, 1], "id": [1, 1, 1]}],
              "shapes": [{"type": "sphere", "center": [0, 0, 3], "radius": 1,
                          "material": {"ks": 0.1, "kd": 0.9, "specularexponent": 10,
                                       "diffusecolor": [1, 0, 0]}}]}
  })");
}

rt::Scene parse(const Json& document) { return rt::parseJsonScene(document.dump(), "mem.json"); }

bool hasWarning(const rt::Scene& scene, const std::string& part) {
  for (const std::string& warning : scene.warnings) {
    if (warning.find(part) != std::string::npos) return true;
  }
  return false;
}

Json& shape0(Json& scene) { return scene["scene"]["shapes"][0]; }

}  // namespace

TEST_SUITE("student dialects") {
  TEST_CASE("shape type spellings: PlanerQuad, rectangle, Traingle, mesh (any case)") {
    const Json quadCorners = {{"point1", {-1, -1, 3}},
                              {"point2", {1, -1, 3}},
                              {"point3", {1, 1, 3}},
                              {"point4", {-1, 1, 3}}};
    for (const char* type : {"PlanerQuad", "planarquad", "rectangle", "Quad"}) {
      CAPTURE(type);
      Json scene = baseScene();
      Json quad = quadCorners;
      quad["type"] = type;
      shape0(scene) = quad;
      const rt::Scene loaded = parse(scene);
      REQUIRE(loaded.shapes.size() == 1);
      CHECK(std::holds_alternative<rt::Quad>(loaded.shapes[0].geometry));
    }
    Json scene = baseScene();
    shape0(scene) = {
        {"type", "Traingle"}, {"point1", {0, 0, 3}}, {"point2", {1, 0, 3}}, {"point3", {0, 1, 3}}};
    CHECK(std::holds_alternative<rt::Triangle>(parse(scene).shapes.at(0).geometry));
    shape0(scene) = {
        {"type", "mesh"}, {"vertices", {{0, 0, 3}, {1, 0, 3}, {0, 1, 3}}}, {"faces", {{0, 1, 2}}}};
    CHECK(std::holds_alternative<rt::MeshInstance>(parse(scene).shapes.at(0).geometry));
  }

  TEST_CASE("quad corners given row by row are read around the quad") {
    Json scene = baseScene();
    shape0(scene) = {{"type", "plane"},
                     {"v0", {-1, -1, 3}},
                     {"v1", {1, -1, 3}},
                     {"v2", {-1, 1, 3}},
                     {"v3", {1, 1, 3}}};
    const rt::Scene loaded = parse(scene);
    const auto& quad = std::get<rt::Quad>(loaded.shapes.at(0).geometry);
    CHECK(quad.v2 == rt::WorldPoint(1, 1, 3));
    CHECK(quad.v3 == rt::WorldPoint(-1, 1, 3));
    CHECK(hasWarning(loaded, "quad corners given row by row"));
  }

  TEST_CASE("camera spellings: thin lens type names, snake_case keys, look_at target") {
    for (const char* type : {"thin_lens", "aperture", "finite-aperture", "ThinLens"}) {
      CAPTURE(type);
      Json scene = baseScene();
      scene["camera"]["type"] = type;
      scene["camera"]["aperture_size"] = 0.2;
      scene["camera"]["focus_distance"] = 3;
      const rt::Scene loaded = parse(scene);
      CHECK(loaded.camera.type == rt::CameraType::ThinLens);
      CHECK(loaded.camera.apertureRadius == doctest::Approx(0.1f));
      CHECK(loaded.camera.focusDistance == doctest::Approx(3.0f));
    }
    Json scene = baseScene();
    scene["camera"]["type"] = "thinlens";
    scene["camera"]["lens_radius"] = 0.05;
    scene["camera"]["focalLength"] = 2;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.05f));
    CHECK(loaded.camera.focusDistance == doctest::Approx(2.0f));

    scene = baseScene();
    scene["camera"].erase("lookat");
    scene["camera"].erase("up");
    scene["camera"]["look_at"] = {0, 0, 5};
    scene["camera"]["up_vector"] = {0, 1, 0};
    loaded = parse(scene);
    CHECK(loaded.camera.forward == glm::vec3(0, 0, 1));
    CHECK(loaded.warnings.empty());
  }

  TEST_CASE("render modes, sample counts and nizqleo's path tracer keys") {
    Json scene = baseScene();
    scene["rendermode"] = "PathTrace";
    CHECK(parse(scene).settings.mode == rt::RenderMode::PathTracer);
    scene = baseScene();
    scene["pixel_sample_num"] = 4;
    scene["path_sample_num"] = 8;
    scene["random"] = 1;
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.mode == rt::RenderMode::PathTracer);
    CHECK(loaded.settings.samplesPerPixel == 32);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Random);
    CHECK(hasWarning(loaded, "pixel_sample_num times path_sample_num"));
  }

  TEST_CASE("nizqleo's 'scale' is its tone map's multiplier: an exposure of scale / 255") {
    Json scene = baseScene();
    scene["scale"] = 1020;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.exposure == doctest::Approx(4.0f));
    CHECK(hasWarning(loaded, "scale: read as an exposure of 4"));
    scene["camera"]["exposure"] = 0.5;  // both: the file's two factors
    CHECK(parse(scene).camera.exposure == doctest::Approx(2.0f));
    scene = baseScene();
    scene["scale"] = 255;  // the usual 0-255 output: nothing read differently
    loaded = parse(scene);
    CHECK(loaded.camera.exposure == 1.0f);
    CHECK(loaded.warnings.empty());
    scene["scale"] = -3;
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("scale"), rt::Error);
  }

  TEST_CASE("a glowing shape ('emittence') is an area light of that radiance") {
    Json scene = baseScene();
    scene["scene"]["lightsources"] = Json::array();
    shape0(scene) = {{"type", "PlanerQuad"},
                     {"point1", {0, 2, 0}},
                     {"point2", {2, 2, 0}},
                     {"point3", {2, 2, 1}},
                     {"point4", {0, 2, 1}},
                     {"emittence", {1, 0.5, 0}},
                     {"material", baseScene()["scene"]["shapes"][0]["material"]}};
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.areaLights.size() == 1);
    CHECK(loaded.areaLights[0].shape == 0);
    CHECK(loaded.areaLights[0].profile == rt::EmissionProfile::Lambertian);
    // Radiance I / (2 A) for a Lambertian light: I = 2 A L with A = 2.
    CHECK(loaded.areaLights[0].diffuseIntensity.x == doctest::Approx(4.0f));
    CHECK(loaded.areaLights[0].diffuseIntensity.y == doctest::Approx(2.0f));
  }

  TEST_CASE("area lights by a corner and two edges, or by centre, normal and size") {
    Json scene = baseScene();
    scene["scene"]["lightsources"] = {{{"type", "arealight"},
                                       {"p", {0, 4, 0}},
                                       {"e0", {1, 0, 0}},
                                       {"e1", {0, 0, 2}},
                                       {"intensity", {1, 1, 1}}},
                                      {{"type", "area"},
                                       {"position", {0, 4, 0}},
                                       {"normal", {0, -1, 0}},
                                       {"w", 2},
                                       {"h", 3},
                                       {"intensity", 1}}};
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.areaLights.size() == 2);
    const auto& edges = std::get<rt::Quad>(loaded.shapes.at(loaded.areaLights[0].shape).geometry);
    CHECK(edges.v2 == rt::WorldPoint(1, 4, 2));
    const auto& facing = std::get<rt::Quad>(loaded.shapes.at(loaded.areaLights[1].shape).geometry);
    CHECK(glm::length(facing.v1 - facing.v0) * glm::length(facing.v3 - facing.v0) ==
          doctest::Approx(6.0f));
    CHECK(glm::dot(glm::cross(facing.v1 - facing.v0, facing.v3 - facing.v0), {0, 1, 0}) != 0.0f);
    CHECK(facing.v0.y == doctest::Approx(4.0f));
    CHECK(loaded.areaLights[1].diffuseIntensity == glm::vec3(1.0f));  // a scalar intensity
  }

  TEST_CASE("missing keys with an obvious default take it, with a warning") {
    Json scene = baseScene();
    shape0(scene)["material"] = {{"diffusecolor", {0, 1, 0}}};
    scene["camera"].erase("type");
    scene["camera"].erase("fov");
    const rt::Scene loaded = parse(scene);
    const rt::Material& m = loaded.materials.at(loaded.shapes.at(0).material);
    CHECK(m.kd == doctest::Approx(0.8f));
    CHECK(m.ks == doctest::Approx(0.2f));
    CHECK(m.specularExponent == doctest::Approx(10.0f));
    CHECK(loaded.camera.type == rt::CameraType::Pinhole);
    CHECK(loaded.camera.fovYDegrees == doctest::Approx(45.0f));
    CHECK(hasWarning(loaded, "scene.shapes[0].material.ks: missing; taken as 0.2"));
    CHECK(hasWarning(loaded, "camera.type: missing; taken as \"pinhole\""));
    CHECK(hasWarning(loaded, "camera.fov: missing; taken as 45 degrees"));
  }

  TEST_CASE("the same warning at several places is one line naming them") {
    Json scene = baseScene();
    Json plain = shape0(scene);
    plain["material"].erase("ks");
    scene["scene"]["shapes"] = {plain, plain, plain, plain, plain};
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.warnings.size() == 1);
    CHECK(loaded.warnings[0] ==
          "mem.json: scene.shapes[0].material.ks, scene.shapes[1].material.ks, "
          "scene.shapes[2].material.ks and 2 more: missing; taken as 0.2");
  }

  TEST_CASE("comments, which JSON lacks, are skipped with a warning") {
    const rt::Scene loaded = rt::parseJsonScene(
        "// a student's note\n" + baseScene().dump() + "\n/* the end */", "mem.json");
    CHECK(loaded.shapes.size() == 1);
    CHECK(hasWarning(loaded, "comments (// or /* */) are not JSON; skipped"));
  }

  TEST_CASE("--strict: the first warning is the error; true errors stay errors") {
    rt::test::TempDir dir;
    Json scene = baseScene();
    shape0(scene)["material"]["texture"] = "C:/Users/someone/wood.ppm";
    const auto file = dir.write("scene.json", scene.dump());
    const rt::Scene lenient = rt::loadSceneFile(file);
    CHECK(hasWarning(lenient, "texture file not found: C:/Users/someone/wood.ppm"));
    try {
      rt::loadSceneFile(file, {true});
      FAIL("--strict must refuse a scene with warnings");
    } catch (const rt::Error& error) {
      const std::string message = error.what();
      CHECK(message.find("texture file not found") != std::string::npos);
      CHECK(message.find("(--strict: every warning is an error)") != std::string::npos);
    }
    scene = baseScene();
    shape0(scene)["material"]["kd"] = "lots";
    const auto wrongType = dir.write("wrong.json", scene.dump());
    CHECK_THROWS_AS(rt::loadSceneFile(wrongType), rt::Error);
    CHECK_NOTHROW(rt::loadSceneFile(dir.write("fine.json", baseScene().dump()), {true}));
  }

  TEST_CASE("more dialects: flat files, lights by position, inline surfaces, polygon lists") {
    // Lights and shapes at the top level; lights without a type; colour x intensity.
    Json flat = baseScene();
    flat["lights"] = {{{"position", {0, 5, 0}}, {"intensity", 2}, {"color", {1, 0.5, 0}}}};
    flat["objects"] = flat["scene"]["shapes"];
    flat.erase("scene");
    rt::Scene loaded = parse(flat);
    CHECK(loaded.shapes.size() == 1);
    REQUIRE(loaded.pointLights.size() == 1);
    CHECK(loaded.pointLights[0].diffuseIntensity == glm::vec3(2, 1, 0));
    CHECK(hasWarning(loaded, "no 'scene' object"));

    Json scene = baseScene();
    scene["scene"]["lightsources"] = {
        {{"type", "arealight"}, {"position", {0, 4, 0}}, {"intensity", {1, 1, 1}}},
        {{"type", "rectlight"},
         {"position", {0, 4, 0}},
         {"u_axis", {0.5, 0, 0}},
         {"v_axis", {0, 0, 0.5}},
         {"intensity", {1, 1, 1}},
         {"num_samples", 8}},
        {{"type", "arealight"},
         {"intensity", {1, 1, 1}},
         {"shape", {{"type", "sphere"}, {"center", {0, 4, 0}}, {"radius", 0.5}}}}};
    loaded = parse(scene);
    CHECK(loaded.pointLights.size() == 1);  // a position alone
    REQUIRE(loaded.areaLights.size() == 2);
    CHECK(loaded.areaLights[0].samples == 8);
    const auto& quad = std::get<rt::Quad>(loaded.shapes.at(loaded.areaLights[0].shape).geometry);
    CHECK(glm::length(quad.v1 - quad.v0) == doctest::Approx(1.0f));
    CHECK(
        std::holds_alternative<rt::Sphere>(loaded.shapes.at(loaded.areaLights[1].shape).geometry));

    scene = baseScene();
    scene["scene"]["shapes"] = {
        {{"type", "triangleMesh"},
         {"vertices", {{0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}}},
         {"faceindex", {4}},
         {"vertexindex", {0, 1, 2, 3}}},
        {{"type", "trimesh"},
         {"vertex", 3},
         {"v0", {0, 0, 3}},
         {"v1", {1, 0, 3}},
         {"v2", {0, 1, 3}},
         {"face", 1},
         {"f0", {0, 1, 2}}},
        {{"type", "rectangle"}, {"corner1", {-1, 0, 1}}, {"corner2", {1, 0, 3}}},
        {{"type", "rectangleXY"}, {"x0", 0}, {"x1", 2}, {"y0", 0}, {"y1", 1}, {"z", 4}}};
    loaded = parse(scene);
    REQUIRE(loaded.shapes.size() == 4);
    CHECK(loaded.meshes.at(0).faces.size() == 2);  // a quad as two triangles
    CHECK(loaded.meshes.at(1).faces.size() == 1);
    const auto& rectangle = std::get<rt::Quad>(loaded.shapes[2].geometry);
    CHECK(rectangle.v1 == rt::WorldPoint(-1, 0, 3));
    CHECK(rectangle.v2 == rt::WorldPoint(1, 0, 3));
    const auto& xy = std::get<rt::Quad>(loaded.shapes[3].geometry);
    CHECK(xy.v2 == rt::WorldPoint(2, 1, 4));
  }

  TEST_CASE("more dialects: lookat as a point, intensity on is/id, a checker texture object") {
    Json scene = baseScene();
    scene["camera"]["position"] = {0, 0, -3};
    scene["camera"]["lookat"] = {0, 0, 0};
    scene["scene"]["lightsources"][0]["intensity"] = 2;
    shape0(scene)["material"]["texture"] = {
        {"type", "checkerboard"}, {"color1", {1, 1, 1}}, {"color2", {0, 0, 0}}, {"scale", 4}};
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.forward == glm::vec3(0, 0, 1));
    CHECK(hasWarning(loaded, "a zero view direction: read as the point looked at"));
    CHECK(loaded.pointLights.at(0).diffuseIntensity == glm::vec3(2.0f));
    const rt::Material& m = loaded.materials.at(0);
    REQUIRE(m.diffuseTexture >= 0);
    CHECK(loaded.textures.at(size_t(m.diffuseTexture)).image.width == 32);  // 4 squares of 8
  }
}

namespace {

// Where an instance puts a vertex of its mesh.
rt::WorldPoint placedVertex(const rt::Scene& scene, size_t shape, size_t vertex) {
  const auto& instance = std::get<rt::MeshInstance>(scene.shapes.at(shape).geometry);
  const glm::dvec3 local(scene.meshes.at(instance.mesh).positions.at(vertex));
  return rt::WorldPoint(instance.objectToWorld * glm::dvec4(local, 1.0));
}

bool near(const rt::WorldPoint& a, const rt::WorldPoint& b) { return glm::length(a - b) < 1e-9; }

}  // namespace

TEST_SUITE("student dialects") {
  TEST_CASE("a spherelight is an area light: a sphere of its radius at its position") {
    Json scene = baseScene();
    scene["scene"]["lightsources"] = Json::parse(
        R"([{"type": "spherelight", "position": [0, 3, 3], "intensity": [1, 1, 1], "radius": 0.25}])");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.areaLights.size() == 1);
    const auto& sphere =
        std::get<rt::Sphere>(loaded.shapes.at(loaded.areaLights[0].shape).geometry);
    CHECK(sphere.center == rt::WorldPoint(0, 3, 3));
    CHECK(sphere.radius == 0.25f);
  }

  TEST_CASE(
      "refractiveindex 0 where nothing refracts reads as 1; where it refracts it is an error") {
    Json scene = baseScene();
    shape0(scene)["material"]["isrefractive"] = false;
    shape0(scene)["material"]["refractiveindex"] = 0.0;
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.materials.at(0).ior == 1.0f);
    CHECK(hasWarning(loaded, "an index of 0 on a surface that does not refract"));
    shape0(scene)["material"]["isrefractive"] = true;
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("refractiveindex: must be positive"),
                         rt::Error);
  }

  TEST_CASE("a mesh given as a list of triangles with corners of their own") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "mesh", "triangles": [
        {"v0": [-1, -1, 3], "v1": [1, -1, 3], "v2": [1, 1, 3]},
        {"v0": [-1, -1, 3], "v1": [1, 1, 3], "v2": [-1, 1, 3]}]})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    CHECK(loaded.meshes[0].faces.size() == 2);
    CHECK(loaded.meshes[0].positions.size() == 6);
    CHECK(near(placedVertex(loaded, 0, 5), {-1, 1, 3}));
    shape0(scene)["triangles"] = Json::array();
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("must list at least one triangle"),
                         rt::Error);
  }

  TEST_CASE("a box by min and max, turned about the world origin as its author's renderer does") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(
        R"({"type": "box", "min": [2, 0, 1], "max": [1, 3, 0], "rotation": [0, 90, 0]})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    CHECK(loaded.meshes[0].positions.size() == 8);
    CHECK(loaded.meshes[0].faces.size() == 12);
    // Corner 0 is (min.x, min.y, min.z) = (2, 0, 1); 90 degrees about y
    // takes (x, z) to (z, -x).
    CHECK(near(placedVertex(loaded, 0, 0), {1, 0, -2}));
    shape0(scene).erase("rotation");
    CHECK(near(placedVertex(parse(scene), 0, 7), {1, 3, 0}));
  }

  TEST_CASE("materials by kind: diffuse, metal, dielectric and emissive") {
    Json scene = baseScene();
    Json& shapes = scene["scene"]["shapes"];
    shapes = Json::array();
    for (const char* material :
         {R"({"type": "diffuse", "albedo": [0.7, 0.2, 0.1]})",
          R"({"type": "metal", "albedo": [0.9, 0.6, 0.3]})",
          R"({"type": "dielectric", "ior": 1.5})",
          R"({"type": "emissive", "colour": [1, 0.5, 0.25], "intensity": 4})"}) {
      shapes.push_back({{"type", "sphere"},
                        {"center", {double(shapes.size()) * 3, 0, 5}},
                        {"radius", 1},
                        {"material", Json::parse(material)}});
    }
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.materials.size() == 4);
    CHECK(loaded.materials[0].diffuseColor == glm::vec3(0.7f, 0.2f, 0.1f));
    CHECK(loaded.materials[0].ks == 0.0f);
    CHECK(loaded.materials[1].reflectivity == doctest::Approx(0.6).scale(0));
    CHECK(loaded.materials[1].kd == 0.0f);
    CHECK(hasWarning(loaded, "a metal's tint is not drawn"));
    CHECK(loaded.materials[2].transmission == 1.0f);
    CHECK(loaded.materials[2].ior == 1.5f);
    REQUIRE(loaded.areaLights.size() == 1);
    CHECK(loaded.areaLights[0].shape == 3);
    CHECK(loaded.areaLights[0].profile == rt::EmissionProfile::Lambertian);
    // Radiance colour * intensity over a sphere of area 4 pi: 2 A L (README "Area lights").
    const float area = 4.0f * 3.14159265f;
    CHECK(loaded.areaLights[0].diffuseIntensity.x == doctest::Approx(2 * area * 4).scale(0));
    CHECK(loaded.areaLights[0].diffuseIntensity.z == doctest::Approx(2 * area * 1).scale(0));
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("a triangle with uv0..uv2 keeps its texture coordinates (a one-triangle mesh)") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "triangle", "v0": [-1, -1, 3], "v1": [1, -1, 3],
        "v2": [1, 1, 3], "uv0": [0, 1], "uv1": [1, 0], "uv2": [1, 1]})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    CHECK(loaded.meshes[0].uvs == std::vector<glm::vec2>{{0, 1}, {1, 0}, {1, 1}});
    CHECK(near(placedVertex(loaded, 0, 2), {1, 1, 3}));
    CHECK_FALSE(hasWarning(loaded, "uv0"));
    shape0(scene)["uv2"] = {1, 1, 1, 1};
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("expected 2 texture coordinates, got 4"),
                         rt::Error);
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("tone curves: tone_mapping in the camera or at the top, use_tone_mapping") {
    Json scene = baseScene();
    CHECK(parse(scene).camera.toneCurve == rt::ToneCurve::Clamp);
    scene["camera"]["tone_mapping"] = "aces";  // constancefr
    CHECK(parse(scene).camera.toneCurve == rt::ToneCurve::Aces);
    scene["camera"]["tone_mapping"] = "hable";
    const rt::Scene unknown = parse(scene);
    CHECK(unknown.camera.toneCurve == rt::ToneCurve::Clamp);
    CHECK(hasWarning(unknown, "unknown tone curve 'hable'"));
    scene["camera"].erase("tone_mapping");
    scene["use_tone_mapping"] = true;  // Kierandon: Reinhard's curve
    CHECK(parse(scene).camera.toneCurve == rt::ToneCurve::Reinhard);
    scene["tonemap"] = "aces";
    CHECK(parse(scene).camera.toneCurve == rt::ToneCurve::Aces);
    scene["use_tone_mapping"] = false;
    CHECK(parse(scene).camera.toneCurve == rt::ToneCurve::Clamp);
    CHECK(rt::toneMappingFor(parse(baseScene())).curve == rt::ToneCurve::Clamp);
  }

  TEST_CASE("renderer switches: stratified sampling read, filters warned, comment keys silent") {
    Json scene = Json::parse(R"({"use_stratified_sampling": false, "use_bvh": true,
        "use_importance_sampling": true, "importance_sampling_min_samples": 50,
        "importance_sampling_max_samples": 100, "use_denoiser": false,
        "use_gaussian_blur": false})");
    scene.update(baseScene());
    shape0(scene)["_comment"] = "the red ball";
    scene["//"] = "a comment";
    rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Random);
    CHECK(loaded.warnings.empty());
    scene["use_stratified_sampling"] = true;
    scene["use_denoiser"] = true;
    loaded = parse(scene);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Jittered);
    CHECK(hasWarning(loaded, "use_denoiser: ignored: the image is the render itself"));
    scene["sampler"] = "sobol";  // a named sampler wins
    CHECK(parse(scene).settings.sampler == rt::SamplerKind::Sobol);
  }

  TEST_CASE("ambientlight: read in Phong mode, warned about in the path tracer") {
    Json scene = baseScene();
    scene["scene"]["ambientlight"] = {0.5, 0.5, 0.25};  // HlnnnWnng
    rt::Scene loaded = parse(scene);
    REQUIRE(loaded.ambientLight.has_value());
    CHECK(*loaded.ambientLight == glm::vec3(0.5f, 0.5f, 0.25f));
    CHECK(rt::lightingConventionsFor(loaded).ambient == glm::vec3(0.5f, 0.5f, 0.25f));
    scene["rendermode"] = "pathtracer";
    loaded = parse(scene);
    CHECK_FALSE(loaded.ambientLight.has_value());
    CHECK(hasWarning(loaded, "the path tracer has no ambient term"));
    scene["scene"]["ambientlight"] = 0.5;
    CHECK_THROWS_AS(parse(scene), rt::Error);
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("an absolute path from the author's machine is found by its tail (chxag)") {
    rt::test::TempDir dir;
    const auto texture = dir.write("project/Code/Textures/wood.ppm", "P6\n1 1\n255\n\x10\x20\x30");
    Json scene = baseScene();
    shape0(scene)["material"]["texture"] = "/Users/someone/Desktop/project/Code/Textures/wood.ppm";
    rt::Scene loaded = rt::loadSceneFile(dir.write("project/Code/Jsons/s.json", scene.dump()));
    CHECK(loaded.materials.at(0).texture == texture);
    CHECK(hasWarning(loaded, "material.texture: the absolute path is not on this machine; using " +
                                 texture.string() + ", found by its tail"));
    shape0(scene)["material"]["texture"] = "C:\\Users\\someone\\project\\Code\\Textures\\wood.ppm";
    loaded = rt::loadSceneFile(dir.write("project/Code/Jsons/windows.json", scene.dump()));
    CHECK(loaded.materials.at(0).texture == texture);
    // A bare file name is looked for only beside the scene, and a tail that
    // is nowhere leaves the texture missing.
    for (const char* elsewhere : {"/Users/someone/other/Textures/stone.ppm", "/wood.ppm"}) {
      CAPTURE(elsewhere);
      shape0(scene)["material"]["texture"] = elsewhere;
      loaded = rt::loadSceneFile(dir.write("project/Code/Jsons/missing.json", scene.dump()));
      CHECK(hasWarning(loaded, "texture file not found"));
    }
  }

  TEST_CASE("texture keys: texturefile, textureFilename with hasTexture, a texture on the shape") {
    Json scene = baseScene();
    for (const char* key : {"texturefile", "textureFilename"}) {  // Nebula1253, david14higgins
      CAPTURE(key);
      Json material = shape0(scene)["material"];
      material[key] = "C:\\Users\\someone\\LAVA.ppm";
      Json withTexture = scene;
      shape0(withTexture)["material"] = material;
      const rt::Scene loaded = parse(withTexture);
      CHECK(loaded.materials.at(0).texture == "C:\\Users\\someone\\LAVA.ppm");
      CHECK(hasWarning(loaded, "texture file not found"));
      material["hasTexture"] = false;
      shape0(withTexture)["material"] = material;
      const rt::Scene off = parse(withTexture);
      CHECK(off.materials.at(0).texture.empty());
      CHECK(off.warnings.empty());
    }
    shape0(scene)["texture"] = "Texture1.ppm";  // bartMn: beside the material
    const rt::Scene onShape = parse(scene);
    CHECK(onShape.materials.at(0).texture == "Texture1.ppm");
    CHECK(hasWarning(onShape, "texture file not found"));
    CHECK_FALSE(hasWarning(onShape, "unknown key"));
  }

  TEST_CASE("a triangle with v0Normal..v2Normal shades with them (a one-triangle mesh)") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "triangle", "v0": [-1, -1, 3], "v1": [1, -1, 3],
        "v2": [1, 1, 3], "v0Normal": [0, 0, -2], "v1Normal": [0, 0.6, -0.8],
        "v2Normal": [0, 0, -1]})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    REQUIRE(loaded.meshes[0].normals.size() == 3);
    CHECK(glm::length(loaded.meshes[0].normals[0] - glm::vec3(0, 0, -1)) < 1e-6f);
    CHECK(glm::length(loaded.meshes[0].normals[1] - glm::vec3(0, 0.6f, -0.8f)) < 1e-6f);
    CHECK(loaded.meshes[0].uvs.empty());
    CHECK_FALSE(hasWarning(loaded, "Normal"));
    shape0(scene)["v1Normal"] = {0, 0, 0};
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("v1Normal"), rt::Error);
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("a camera animated through key positions renders its first frame, with a warning") {
    Json scene = baseScene();
    scene["FramesNum"] = 250;  // bartMn
    scene["camera"].erase("position");
    scene["camera"]["position0"] = {-2.0, 0.0, 2.25};
    scene["camera"]["position1"] = {0.0, 0.75, -0.25};
    scene["camera"]["movement0"] = {0, 125};
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.position == rt::WorldPoint(-2.0, 0.0, 2.25));
    CHECK(hasWarning(loaded, "an animated camera of 2 key positions"));
    CHECK_FALSE(hasWarning(loaded, "unknown key"));
    scene["camera"]["position1"] = {0, "x", 0};
    CHECK_THROWS_AS(parse(scene), rt::Error);
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("a mesh of vertices without faces is a triangle strip (Seanst98), UVs of 3") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "trimesh",
        "points": [[-1, -1, 3], [1, -1, 3], [-1, 1, 3], [1, 1, 3]],
        "texturecoordinates": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    CHECK(loaded.meshes[0].faces == std::vector<glm::uvec3>{{0, 1, 2}, {1, 2, 3}});
    CHECK(loaded.meshes[0].uvs.at(3) == glm::vec2(1, 1));
    shape0(scene)["points"] = Json::parse("[[0, 0, 3], [1, 0, 3]]");
    shape0(scene).erase("texturecoordinates");
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("fewer than 3 vertices"), rt::Error);
  }

  TEST_CASE("Seanst98's thin lens (ap, f), isGlass as a string, sampling inside the scene") {
    Json scene = baseScene();
    scene["camera"]["type"] = "thinlens";
    scene["camera"]["ap"] = 0.2;
    scene["camera"]["f"] = 4;
    shape0(scene)["material"]["isGlass"] = "true";
    shape0(scene)["material"]["refractiveIndex"] = 1.3;
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.type == rt::CameraType::ThinLens);
    CHECK(loaded.camera.apertureRadius == doctest::Approx(0.1).scale(0));
    CHECK(loaded.camera.focusDistance == 4.0f);
    CHECK(loaded.materials.at(0).transmission == 1.0f);
    CHECK(loaded.materials.at(0).ior == 1.3f);
    shape0(scene)["material"]["isGlass"] = "false";
    CHECK(parse(scene).materials.at(0).transmission == 0.0f);
    shape0(scene)["material"]["isGlass"] = "maybe";
    CHECK_THROWS_WITH_AS(parse(scene), doctest::Contains("isGlass: expected a boolean"), rt::Error);
  }

  TEST_CASE("Trenza1ore: area light size [a, b], an ambient light, PLY offset, scale and euler") {
    Json scene = baseScene();
    scene["scene"]["lightsources"] = Json::parse(R"([
        {"type": "arealight", "position": [0, 3, 3], "intensity": [1, 1, 1], "size": [0.5, 0.25]},
        {"type": "ambient", "intensity": [0.2, 0.3, 0.4]}])");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.areaLights.size() == 1);
    const auto& quad = std::get<rt::Quad>(loaded.shapes.at(loaded.areaLights[0].shape).geometry);
    CHECK(near(quad.v0, {-0.5, 3, 2.75}));  // 2a by 2b on x and z, centred, facing down
    CHECK(near(quad.v2, {0.5, 3, 3.25}));
    CHECK(glm::cross(quad.v1 - quad.v0, quad.v3 - quad.v0).y < 0.0);
    REQUIRE(loaded.ambientLight.has_value());
    CHECK(*loaded.ambientLight == glm::vec3(0.2f, 0.3f, 0.4f));
    for (const char* type : {"uvsphere", "cubemap", "sphericalmap"}) {
      shape0(scene)["type"] = type;
      CHECK(std::holds_alternative<rt::Sphere>(parse(scene).shapes.at(0).geometry));
    }
    const rt::test::TempDir temp;
    const std::filesystem::path dir = temp.path();
    temp.write("tri.ply",
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
    shape0(scene) = Json::parse(R"({"type": "ply", "path": "tri.ply", "offset": [1, 2, 3],
        "scale": [2, 3, 4], "euler": [0, 0, 90]})");
    const rt::Scene placed = rt::parseJsonScene(scene.dump(), dir / "scene.json");
    // (1, 0, 0) turned 90 degrees about z is (0, 1, 0), scaled (0, 3, 0), moved (1, 5, 3).
    CHECK(near(placedVertex(placed, 0, 0), {1, 5, 3}));
    CHECK(near(placedVertex(placed, 0, 2), {1, 2, 7}));
  }

  TEST_CASE("an area light without area (an edge of length 0) is a point light at its centre") {
    Json scene = baseScene();
    scene["scene"]["lightsources"] = Json::parse(R"([{"type": "rectlight", "position": [0, 2, 1],
        "u": [1, 0, 0], "v": [0, 0, 0], "width": 2, "height": 2, "intensity": [3, 3, 3]}])");
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.areaLights.empty());
    REQUIRE(loaded.pointLights.size() == 1);
    CHECK(near(loaded.pointLights[0].position, {0, 2, 1}));
    CHECK(loaded.pointLights[0].diffuseIntensity == glm::vec3(3.0f));
    CHECK(hasWarning(loaded, "an area light without area"));
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("the textbook camera: lookfrom, lookat a point, vup (sukriti27)") {
    Json scene = baseScene();
    scene["camera"] = Json::parse(R"({"type": "pinhole", "width": 32, "height": 24, "fov": 45,
        "lookfrom": [0, 0, 5], "lookat": [0, 0, 3], "vup": [0, 1, 0]})");
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.position == rt::WorldPoint(0, 0, 5));
    // A point: from (0, 0, 5) towards (0, 0, 3), not the direction (0, 0, 3).
    CHECK(loaded.camera.forward == glm::vec3(0, 0, -1));
    CHECK(!hasWarning(loaded, "unknown key"));
  }

  TEST_CASE("camPos, camView (a direction) and camAxis (acs107102)") {
    Json scene = baseScene();
    scene["camera"] = Json::parse(R"({"type": "pinhole", "width": 32, "height": 24, "fov": 35,
        "camPos": [0, -3.5, 2], "camView": [0, 1, 0], "camAxis": [0, 0, 0.5]})");
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.camera.position == rt::WorldPoint(0, -3.5, 2));
    // Read as the view, not replaced by the default view (which was parallel to up).
    CHECK(loaded.camera.forward == glm::vec3(0, 1, 0));
    CHECK(loaded.camera.up == glm::vec3(0, 0, 0.5f));
  }

  TEST_CASE("sample_number, use_jitter_sample (IrwinChay), camera samplesize (Vergilc)") {
    Json scene = baseScene();
    scene["sample_number"] = 12;
    scene["use_jitter_sample"] = false;
    rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.samplesPerPixel == 12);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Random);
    scene = baseScene();
    scene["camera"]["samplesize"] = 9;
    loaded = parse(scene);
    CHECK(loaded.settings.samplesPerPixel == 9);
  }

  TEST_CASE("a triangle's uv1..uv3 beside corners v1..v3 (sukriti27)") {
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "triangle", "v1": [0, 0, 3], "v2": [1, 0, 3],
        "v3": [0, 1, 3], "uv1": [0.5, 0.1], "uv2": [0.1, 0.9], "uv3": [0.9, 0.9],
        "material": {"ks": 0, "kd": 1, "specularexponent": 3, "diffusecolor": [1, 1, 1]}})");
    const rt::Scene loaded = parse(scene);
    REQUIRE(loaded.meshes.size() == 1);
    REQUIRE(loaded.meshes[0].uvs.size() == 3);
    CHECK(loaded.meshes[0].uvs[0] == glm::vec2(0.5f, 0.1f));
    CHECK(loaded.meshes[0].uvs[2] == glm::vec2(0.9f, 0.9f));
  }

  TEST_CASE("a mesh file placed by `position` (IrwinChay)") {
    rt::test::TempDir dir;
    dir.write("tri.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    Json scene = baseScene();
    shape0(scene) = Json::parse(R"({"type": "mesh", "path": "tri.ply", "position": [1, 2, 3],
        "vs": 3, "fs": 1,
        "material": {"ks": 0, "kd": 1, "specularexponent": 3, "diffusecolor": [1, 1, 1]}})");
    const rt::Scene loaded = rt::parseJsonScene(scene.dump(), dir.path() / "scene.json");
    REQUIRE(loaded.shapes.size() == 1);
    CHECK(near(placedVertex(loaded, 0, 1), {2, 2, 3}));
    CHECK(!hasWarning(loaded, "unknown key"));
  }
}

TEST_SUITE("student dialects") {
  TEST_CASE("named materials and textures, cameraToWorld, an infinite plane (isaacery)") {
    Json scene = baseScene();
    scene["sampling"] = "grid";
    scene["camera"] = Json::parse(R"({"type": "thinlens", "width": 32, "height": 32, "fov": 50,
        "cameraToWorld": [1, 0, 0, 0,  0, 0.6, 0.8, 4,  0, -0.8, 0.6, 0,  0, 0, 0, 1],
        "radius": 0.2, "focus": 5})");
    scene["scene"]["backgroundcolour"] = {0.1, 0.2, 0.3};
    scene["scene"]["ambient"] = 0.25;
    scene["scene"]["textures"] = Json::parse(R"([
        {"name": "green", "type": "constant", "colour": [0.04, 0.42, 0.01]},
        {"name": "ball", "type": "image", "image": "Ball1.jpg", "offset_u": 0.4, "offset_v": 0.9}])");
    scene["scene"]["materials"] = Json::parse(R"([
        {"name": "floor", "type": "blinnphong", "ka": 0, "ks": 0, "kd": 0.75, "alpha": 5,
         "reflectance": 0, "texture": "green"},
        {"name": "ball", "type": "blinnphong", "ka": 0.2, "ks": 0.8, "kd": 0.8, "alpha": 8,
         "reflectance": 0.5, "texture": "ball"}])");
    scene["scene"]["shapes"] = Json::parse(R"([
        {"type": "sphere", "radius": 1, "center": [-1, 0, -3], "material": "ball"},
        {"type": "sphere", "radius": 1, "center": [1, 0, -3], "material": "ball"},
        {"type": "plane", "distance": -1, "normal": [0, 1, 0], "material": "floor"}])");
    const rt::Scene loaded = parse(scene);
    CHECK(loaded.settings.sampler == rt::SamplerKind::Jittered);
    CHECK(loaded.backgroundColor == glm::vec3(0.1f, 0.2f, 0.3f));
    // Camera space looks down -z with y up; the matrix's last column places it.
    CHECK(loaded.camera.position == rt::WorldPoint(0, 4, 0));
    CHECK(glm::length(loaded.camera.forward - glm::vec3(0, -0.8f, -0.6f)) < 1e-6f);
    CHECK(loaded.camera.type == rt::CameraType::ThinLens);
    CHECK(loaded.camera.apertureRadius == 0.2f);
    CHECK(loaded.camera.focusDistance == 5.0f);
    REQUIRE(loaded.shapes.size() == 3);
    // Both balls share the one named material.
    CHECK(loaded.shapes[0].material == loaded.shapes[1].material);
    const rt::Material& ball = loaded.materials[loaded.shapes[0].material];
    CHECK(ball.specularExponent == 8.0f);
    CHECK(ball.reflectivity == 0.5f);
    CHECK(ball.diffuseTexture >= 0);  // the missing-texture squares
    const rt::Material& floor = loaded.materials[loaded.shapes[2].material];
    CHECK(floor.diffuseColor == glm::vec3(0.04f, 0.42f, 0.01f));
    const auto& plane = std::get<rt::Quad>(loaded.shapes[2].geometry);
    CHECK(plane.v0.y == -1.0);
    CHECK(std::abs(plane.v0.x) == 1e4);
    for (const char* warning : {"texture file not found: Ball1.jpg", "texture offsets are not read",
                                "an infinite plane", "'ka' ignored", "scene.ambient: ignored"}) {
      CAPTURE(warning);
      CHECK(hasWarning(loaded, warning));
    }
  }

  TEST_CASE("a shape naming a material that was not defined names the key") {
    Json scene = baseScene();
    shape0(scene)["material"] = "nowhere";
    CHECK_THROWS_WITH_AS(parse(scene),
                         doctest::Contains("scene.shapes[0].material: no material named 'nowhere'"),
                         rt::Error);
  }
}
