// Blender scene exports of a later coursework (formats/json/BlenderExport):
// each layout students' exporters wrote, on small files written for this
// suite, read into Blender's camera, units and primitives.
#include <doctest/doctest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "formats/json/JsonSceneLoader.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

namespace {

rt::Scene parse(const std::string& text) { return rt::parseJsonScene(text, "export.json"); }

bool near(glm::dvec3 a, glm::dvec3 b, double tolerance = 1e-4) {
  return glm::length(a - b) <= tolerance;
}
bool near(glm::vec3 a, glm::dvec3 b) { return near(glm::dvec3(a), b); }

bool hasWarning(const rt::Scene& scene, const std::string& part) {
  for (const std::string& warning : scene.warnings) {
    if (warning.find(part) != std::string::npos) return true;
  }
  return false;
}

// Where a mesh instance puts a point of its object space.
glm::dvec3 placed(const rt::MeshInstance& instance, glm::dvec3 p) {
  return glm::dvec3(instance.objectToWorld * glm::dvec4(p, 1.0));
}

// Vertical field of view of a 50 mm lens whose 36 mm sensor spans the
// width of a 16:9 image (Blender's AUTO fit on a landscape image).
const double kLandscapeFov50 = glm::degrees(2.0 * std::atan(18.0 / 50.0 * 9.0 / 16.0));

}  // namespace

TEST_SUITE("Blender exports") {
  TEST_CASE("lists at the top level: camera, point light in watts, sphere, cube, plane") {
    const rt::Scene scene = parse(R"({
      "cameras": [{"location": [7, -6, 4], "gaze_vector": [-0.6, 0.6, -0.5],
                   "up_vector": [0, 0, 1], "focal_length": 50, "sensor_width": 36,
                   "sensor_height": 24, "film_resolution": [160, 90]}],
      "point_lights": [{"location": [4, 1, 6], "radiant_intensity": 1000}],
      "spheres": [{"location": [1, 2, 3], "radius": 0.5,
                   "material": {"kd": [1, 0, 0], "ks": [1, 1, 1], "shininess": 64,
                                "reflectivity": 0.25, "transmissive": 0.5, "ior": 1.5}}],
      "cubes": [{"translation": [0, 0, 1], "rotation": [0, 0, 1.5707963], "scale": 2}],
      "planes": [{"corners": [[-1, -1, 0], [1, -1, 0], [-1, 1, 0], [1, 1, 0]]}]
    })");
    CHECK(scene.conventions == rt::Conventions::Physical);
    CHECK(scene.conventionsReason.find("Blender") != std::string::npos);
    CHECK(scene.warnings.empty());
    CHECK(scene.camera.width == 160);
    CHECK(scene.camera.height == 90);
    CHECK(near(scene.camera.position, {7, -6, 4}));
    CHECK(near(scene.camera.forward, glm::normalize(glm::dvec3(-0.6, 0.6, -0.5))));
    CHECK(scene.camera.fovYDegrees == doctest::Approx(kLandscapeFov50).epsilon(1e-5));
    REQUIRE(scene.pointLights.size() == 1);
    // 1000 W is 1000 / (4 pi) W/sr; the physical conventions' I lights as I / 4 W/sr.
    CHECK(scene.pointLights[0].diffuseIntensity.x == doctest::Approx(1000.0 / glm::pi<double>()));
    REQUIRE(scene.shapes.size() == 3);
    const auto& sphere = std::get<rt::Sphere>(scene.shapes[0].geometry);
    CHECK(near(sphere.center, {1, 2, 3}));
    CHECK(sphere.radius == 0.5f);
    const rt::Material& glass = scene.materials[scene.shapes[0].material];
    CHECK(glass.diffuseColor == glm::vec3(1, 0, 0));
    CHECK(glass.specularExponent == 64.0f);
    CHECK(glass.reflectivity == 0.25f);
    CHECK(glass.transmission == 0.5f);
    CHECK(glass.ior == 1.5f);
    // Blender's cube is [-1, 1]^3: scale 2, a quarter turn about z, raised by 1.
    const auto& cube = std::get<rt::MeshInstance>(scene.shapes[1].geometry);
    CHECK(near(placed(cube, {1, 1, 1}), {-2, 2, 3}));
    CHECK(near(placed(cube, {-1, -1, -1}), {2, -2, -1}));
    CHECK(scene.meshes[cube.mesh].faces.size() == 12);
    // Corners in Blender's vertex order are read around the quad.
    const auto& plane = std::get<rt::Quad>(scene.shapes[2].geometry);
    CHECK(near(plane.v2, {1, 1, 0}));
    CHECK(near(plane.v3, {-1, 1, 0}));
  }

  TEST_CASE("everything inside `properties`, vectors and colours as objects (shleem0)") {
    const rt::Scene scene = parse(R"({"properties": {
      "cameras": [{"location": {"x": 9, "y": -8, "z": 8}, "gaze_vector": {"x": -1, "y": 0, "z": 0},
                   "up_vector": {"x": 0, "y": 0, "z": 1}, "focal_length": 35,
                   "sensor": {"width": 36, "height": 24},
                   "film_resolution": {"width": 64, "height": 64}}],
      "point_lights": [{"location": {"x": 5, "y": 0, "z": 5}, "radiant_intensity": 100}],
      "spheres": [{"location": {"x": 3, "y": 4, "z": 0}, "radius": 1,
                   "material": {"diffuse": {"r": 0, "g": 0, "b": 0.8},
                                "specular": {"r": 1, "g": 1, "b": 1}, "shininess": 64,
                                "transparency": 0, "ior": 1.5, "texture": null}}],
      "cubes": [], "planes": []}})");
    CHECK(scene.warnings.empty());
    CHECK(near(scene.camera.position, {9, -8, 8}));
    // A square image under AUTO fit: the sensor width spans both sides.
    CHECK(scene.camera.fovYDegrees ==
          doctest::Approx(glm::degrees(2.0 * std::atan(18.0 / 35.0))).epsilon(1e-5));
    REQUIRE(scene.shapes.size() == 1);
    CHECK(scene.materials[scene.shapes[0].material].diffuseColor == glm::vec3(0, 0, 0.8f));
    CHECK(scene.materials[scene.shapes[0].material].diffuseTexture == -1);
  }

  TEST_CASE("typed objects: CAMERA, LIGHT with id/is, MESH shapes, 8-bit colours (James-h-1969)") {
    const rt::Scene scene = parse(R"({"scene_name": "Scene", "objects": [
      {"name": "Camera", "type": "CAMERA", "location": [0, -10, 0],
       "gaze_vector_direction": [0, 1, 0], "up_vector": [0, 0, 1], "focal_length": 50,
       "sensor_width": 36, "sensor_height": 24, "sensor_fit": "VERTICAL",
       "film_resolution": [64, 48]},
      {"name": "Light", "type": "LIGHT", "location": [0, 0, 5], "id": 47.75, "is": 20},
      {"name": "Cube", "type": "MESH", "shape": "CUBE", "translation": [0, 0, 0],
       "rotation_euler_rad": [0, 0, 0], "scale": [1, 2, 3],
       "material": {"ka": 0.1, "kd": 0.9, "ks": 0.5, "shininess": 100, "reflectivity": 0,
                    "transparancy": 0, "ior": 1, "base_colour": [255, 128, 0]}},
      {"name": "Sphere", "type": "MESH", "shape": "SPHERE", "location": [2, 0, 0],
       "rotation_euler_rad": [0, 0, 0], "scale": [1, 1, 2]},
      {"name": "Plane", "type": "MESH", "shape": "PLANE",
       "corners_world": [[-3, -3, -1], [3, -3, -1], [3, 3, -1], [-3, 3, -1]]}]})");
    CHECK(scene.warnings.empty());
    // VERTICAL fit: the 24 mm sensor height spans the image height.
    CHECK(scene.camera.fovYDegrees ==
          doctest::Approx(glm::degrees(2.0 * std::atan(12.0 / 50.0))).epsilon(1e-5));
    REQUIRE(scene.pointLights.size() == 1);
    CHECK(scene.pointLights[0].diffuseIntensity.x == doctest::Approx(4 * 47.75));
    CHECK(scene.pointLights[0].specularIntensity.x == doctest::Approx(4 * 20.0));
    REQUIRE(scene.shapes.size() == 3);
    const rt::Material& orange = scene.materials[scene.shapes[0].material];
    CHECK(orange.diffuseColor.x == doctest::Approx(1.0));
    CHECK(orange.diffuseColor.y == doctest::Approx(128.0 / 255.0));
    CHECK(orange.kd == doctest::Approx(0.9));
    CHECK(orange.ks == doctest::Approx(0.5));
    const auto& box = std::get<rt::MeshInstance>(scene.shapes[0].geometry);
    CHECK(near(placed(box, {1, 1, 1}), {1, 2, 3}));
    // A non-uniform scale makes an ellipsoid: a sphere mesh, placed.
    const auto& ellipsoid = std::get<rt::MeshInstance>(scene.shapes[1].geometry);
    CHECK(near(placed(ellipsoid, {0, 0, 1}), {2, 0, 2}));
    CHECK(scene.meshes[ellipsoid.mesh].normals.size() ==
          scene.meshes[ellipsoid.mesh].positions.size());
    CHECK(std::holds_alternative<rt::Quad>(scene.shapes[2].geometry));
  }

  TEST_CASE("a bare list of objects: camera turned by Euler angles, no light power, a metaball") {
    const rt::Scene scene = parse(R"([
      {"name": "Camera", "type": "CAMERA", "location": [0, -5, 0],
       "rotation_euler_radians": [1.5707963, 0, 0], "scale": [1, 1, 1],
       "camera_properties": {"lens_type": "PERSP", "focal_length_mm": 50, "sensor_fit": "AUTO",
                             "sensor_width_mm": 36, "sensor_height_mm": 24, "shift_x": 0,
                             "shift_y": 0, "clip_start": 0.1, "clip_end": 100}},
      {"name": "Light", "type": "LIGHT", "location": [0, 0, 4], "rotation_euler_radians": [0, 0, 0],
       "scale": [1, 1, 1], "material_base_color_rgb": null},
      {"name": "Cube.001", "type": "MESH", "location": [0, 0, 0],
       "rotation_euler_radians": [0, 0, 0], "scale": [1, 1, 1],
       "material_base_color_rgb": [0.2, 0.4, 0.6]},
      {"name": "Mball", "type": "META", "location": [0, 0, 2], "scale": [0.5, 0.5, 0.5]},
      {"name": "Empty", "type": "EMPTY", "location": [0, 0, 0]}])");
    // Turned 90 degrees about x, Blender's camera looks down +y with +z up.
    CHECK(near(scene.camera.forward, {0, 1, 0}));
    CHECK(near(scene.camera.up, {0, 0, 1}));
    CHECK(scene.camera.width == 1920);
    CHECK(hasWarning(scene, "no film resolution"));
    CHECK(hasWarning(scene, "no light power: Blender's default 1000 W"));
    CHECK(hasWarning(scene, "a metaball"));
    CHECK(hasWarning(scene, "\"EMPTY\""));
    REQUIRE(scene.shapes.size() == 2);
    CHECK(scene.materials[scene.shapes[0].material].diffuseColor == glm::vec3(0.2f, 0.4f, 0.6f));
    CHECK(std::get<rt::Sphere>(scene.shapes[1].geometry).radius == 0.5f);
  }

  TEST_CASE("objects grouped by Blender type with ids (kailen-hargenrader), a cylinder") {
    const rt::Scene scene = parse(R"({
      "MESH": {"Cylinder": {"1": {"translation": {"x": 0, "y": 0, "z": 1},
                                  "rotation": {"roll": 1.5707963, "pitch": 0, "yaw": 0},
                                  "scale": {"x": 0.5, "y": 0.5, "z": 2}}},
               "Torus": {"2": {"translation": {"x": 0, "y": 0, "z": 0}}}},
      "CAMERA": {"PERSP": {"3": {"location": {"x": 0, "y": -8, "z": 1},
                                 "direction": {"x": 0, "y": 1, "z": 0}, "focal_length": 50,
                                 "sensor_width": 36, "sensor_height": 24,
                                 "film_resolution": {"x": 32, "y": 18}}}},
      "LIGHT": {"POINT": {"4": {"location": {"x": 0, "y": 0, "z": 5}, "radiant_intensity": 10,
                                "radius": 0.25}}}})");
    // A gaze without up: Blender's world up, +z.
    CHECK(near(scene.camera.up, {0, 0, 1}));
    CHECK(hasWarning(scene, "a mesh this renderer does not read"));
    REQUIRE(scene.shapes.size() ==
            2);  // the light's sphere (lights are read first) and the cylinder
    const auto& cylinder = std::get<rt::Cylinder>(scene.shapes[1].geometry);
    CHECK(near(cylinder.axis, {0, -1, 0}));
    CHECK(cylinder.radius == 0.5f);
    CHECK(cylinder.halfHeight == 2.0f);
    // A light with a radius: a spherical area light of the same power.
    CHECK(scene.pointLights.empty());
    REQUIRE(scene.areaLights.size() == 1);
    CHECK(std::get<rt::Sphere>(scene.shapes[scene.areaLights[0].shape].geometry).radius == 0.25f);
    CHECK(scene.areaLights[0].diffuseIntensity.x == doctest::Approx(10.0 / glm::pi<double>()));
  }

  TEST_CASE("no camera: Blender's startup camera; a texture that is not there") {
    const rt::Scene scene = parse(R"({"Mesh": {"Plane": [{"corners": [[-1, -1, 0], [1, -1, 0],
        [1, 1, 0], [-1, 1, 0]], "material": {"baseColor": {"type": "ImageTexture",
        "path": "Textures/missing.png"}}}]}, "Light": {"Point": [{"location": [0, 0, 3],
        "radiantIntensity": 10}]}})");
    CHECK(hasWarning(scene, "no camera: Blender's default camera"));
    CHECK(near(scene.camera.position, {7.3589, -6.9258, 4.9583}));
    // It looks at the origin, as in Blender's startup file.
    const glm::dvec3 toOrigin = glm::normalize(-scene.camera.position);
    CHECK(glm::dot(glm::dvec3(scene.camera.forward), toOrigin) > 0.999);
    CHECK(hasWarning(scene, "texture file not found: Textures/missing.png"));
    CHECK(scene.materials[scene.shapes[0].material].diffuseTexture >= 0);
  }

  TEST_CASE("bad values name their key") {
    CHECK_THROWS_WITH_AS(parse(R"({"cameras": [{"location": [0, 0, 5], "gaze": [0, 0, 0]}]})"),
                         doctest::Contains("cameras[0].gaze: the gaze vector has no direction"),
                         rt::Error);
    CHECK_THROWS_WITH_AS(parse(R"({"cameras": [{"location": [0, 0, 5], "gaze": [0, 0, -1]}],
                  "planes": [{"corners": [[0, 0, 0], [1, 0, 0]]}]})"),
                         doctest::Contains("planes[0].corners: expected 4 corners, got 2"),
                         rt::Error);
    CHECK_THROWS_WITH_AS(
        parse(R"({"cameras": [{"location": [0, 0, 5], "gaze": [0, 0, -1], "focal_length": -5}]})"),
        doctest::Contains("cameras[0].focal_length"), rt::Error);
    CHECK_THROWS_WITH_AS(parse(R"({"cameras": [{"location": [0, 0, 5], "gaze": [0, 0, -1]}],
                  "point_lights": [{"radiant_intensity": 5}]})"),
                         doctest::Contains("point_lights[0]: missing 'location'"), rt::Error);
  }

  TEST_CASE("a coursework camera with a `location` key is not taken for a Blender export") {
    const rt::Scene scene = parse(R"({
      "camera": {"type": "pinhole", "width": 32, "height": 24, "fov": 45, "location": [0, 0, 0],
                 "position": [0, 0, 0], "lookat": [0, 0, 1], "up": [0, 1, 0]},
      "scene": {"lightsources": [], "shapes": []}})");
    CHECK(scene.conventions != rt::Conventions::Physical);
  }
}
