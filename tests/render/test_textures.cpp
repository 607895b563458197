// Texture mapping end to end: UV conventions per shape, bilinear filtering,
// repeat wrapping and sRGB decoding, through the real render kernel.
#include <doctest/doctest.h>

#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

// A 2x2 texture: red, green on the top row; blue, grey (sRGB 128) below.
Texture quadrantTexture() {
  return {"quadrants",
          {2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 128, 128, 128, 255}}};
}

// Camera on +z looking at the origin (image right = +x), a light at the
// camera far enough that n.l = 1 over the view, no falloff, pure diffuse:
// every pixel shows the texture's linear colour.
Scene flatLitScene() {
  Scene scene;
  scene.conventions = Conventions::Textbook;
  scene.camera.width = 256;
  scene.camera.height = 256;
  scene.camera.position = {0, 0, 1000};
  scene.camera.forward = {0, 0, -1};
  scene.camera.fovYDegrees = 2.0f * glm::degrees(std::atan(1.0f / 1000.0f));  // sees [-1, 1]^2
  scene.pointLights.push_back({{0, 0, 1e6f}, glm::vec3(1), glm::vec3(0)});
  Material material;
  material.kd = 1;
  material.ks = 0;
  material.diffuseTexture = 0;
  scene.materials.push_back(material);
  scene.textures.push_back(quadrantTexture());
  return scene;
}

glm::vec3 renderedAt(const ImageF& image, float u, float v) {
  const float* p = image.pixel(uint32_t(u * float(image.width)), uint32_t(v * float(image.height)));
  return {p[0], p[1], p[2]};
}

ImageF render(const Scene& scene) {
  RenderOptions options;
  options.samplesPerPixel = 1;
  return test::render(scene, options);
}

void checkColor(glm::vec3 actual, glm::vec3 expected) {
  CAPTURE(actual.x);
  CAPTURE(actual.y);
  CAPTURE(actual.z);
  // A pixel spans 1/128 of a texel (1/64 on the repeated mesh): bilinear
  // filtering mixes in at most that much of the neighbour.
  CHECK(glm::all(glm::lessThan(glm::abs(actual - expected), glm::vec3(0.02f))));
}

constexpr float kGreyLinear = 0.21586f;  // sRGB 128 decoded

}  // namespace

TEST_SUITE("render textures") {
  TEST_CASE("a quad maps v0 to uv (0,0), v1 to (1,0), v3 to (0,1), decoded from sRGB") {
    Scene scene = flatLitScene();
    Shape quad;
    quad.geometry = Quad{{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    scene.shapes.push_back(quad);
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.25f), {1, 0, 0});
    checkColor(renderedAt(image, 0.75f, 0.25f), {0, 1, 0});
    checkColor(renderedAt(image, 0.25f, 0.75f), {0, 0, 1});
    checkColor(renderedAt(image, 0.75f, 0.75f), glm::vec3(kGreyLinear));
    // Bilinear filtering: half way between red and green texel centres.
    glm::vec3 middle = renderedAt(image, 0.5f, 0.25f);
    CHECK(middle.x == doctest::Approx(0.5).epsilon(0.1).scale(0));
    CHECK(middle.y == doctest::Approx(0.5).epsilon(0.1).scale(0));
  }

  TEST_CASE("mesh UVs beyond [0,1] repeat the texture") {
    Scene scene = flatLitScene();
    TriangleMesh mesh;
    mesh.positions = {{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    mesh.uvs = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    mesh.faces = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
    Shape shape;
    shape.geometry = MeshInstance{0, WorldTransform(1.0)};
    scene.shapes.push_back(shape);
    ImageF image = render(scene);
    // Two repeats across: red at 1/8 and at 5/8 of the width.
    checkColor(renderedAt(image, 0.125f, 0.125f), {1, 0, 0});
    checkColor(renderedAt(image, 0.625f, 0.125f), {1, 0, 0});
    checkColor(renderedAt(image, 0.375f, 0.875f), glm::vec3(kGreyLinear));
    checkColor(renderedAt(image, 0.375f, 0.625f), {0, 1, 0});
  }

  TEST_CASE("a texture multiplies the colour only where the material says so") {
    Scene scene = flatLitScene();
    scene.materials[0].diffuseColor = {0.5f, 0.5f, 0.5f};
    Shape quad;
    quad.geometry = Quad{{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    scene.shapes.push_back(quad);
    checkColor(renderedAt(render(scene), 0.25f, 0.25f), {1, 0, 0});  // replaced (coursework)
    scene.materials[0].textureTintedByColor = true;                  // glTF base colour
    checkColor(renderedAt(render(scene), 0.25f, 0.25f), {0.5f, 0, 0});
  }

  TEST_CASE("vertex colours multiply the textured colour, interpolated across the faces") {
    Scene scene = flatLitScene();
    scene.materials[0].diffuseColor = {0.5f, 0.5f, 0.5f};
    scene.materials[0].textureTintedByColor = true;
    TriangleMesh mesh;
    mesh.positions = {{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.faces = {{0, 1, 2}, {0, 2, 3}};
    mesh.colors = {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, {1, 1, 0}};  // yellow
    scene.meshes.push_back(mesh);
    Shape shape;
    shape.geometry = MeshInstance{0, WorldTransform(1.0)};
    scene.shapes.push_back(shape);
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.25f), {0.5f, 0, 0});  // red texel
    checkColor(renderedAt(image, 0.75f, 0.25f), {0, 0.5f, 0});  // green
    checkColor(renderedAt(image, 0.25f, 0.75f), {0, 0, 0});     // blue: no blue in yellow

    // Untextured, red on the left edge and blue on the right: a linear blend.
    scene.materials[0].diffuseTexture = -1;
    scene.materials[0].diffuseColor = glm::vec3(1.0f);
    scene.textures.clear();
    scene.meshes[0].colors = {{1, 0, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}};
    image = render(scene);
    checkColor(renderedAt(image, 0.05f, 0.5f), {0.95f, 0, 0.05f});
    checkColor(renderedAt(image, 0.5f, 0.3f), {0.5f, 0, 0.5f});
    checkColor(renderedAt(image, 0.95f, 0.7f), {0.05f, 0, 0.95f});
  }
}
