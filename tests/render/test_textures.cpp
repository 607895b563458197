// Texture mapping end to end: UV conventions per shape, bilinear filtering,
// repeat wrapping and sRGB decoding, through the real render kernel.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

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

// The square [-1, 1]^2 in z = 0 as a mesh with texture coordinates `uvs`
// at its corners (top left, top right, bottom right, bottom left as the
// camera sees them); the default faces turn clockwise as the camera sees
// them (the back: triangles are two-sided), {{0, 2, 1}, {0, 3, 2}} the other way.
TriangleMesh squareMesh(std::vector<glm::vec2> uvs,
                        std::vector<glm::uvec3> faces = {{0, 1, 2}, {0, 2, 3}}) {
  TriangleMesh mesh;
  mesh.positions = {{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
  mesh.uvs = std::move(uvs);
  mesh.faces = std::move(faces);
  return mesh;
}

// `mesh` placed once, in world space.
void addMesh(Scene& scene, TriangleMesh mesh) {
  scene.meshes.push_back(std::move(mesh));
  Shape shape;
  shape.geometry = MeshInstance{uint32_t(scene.meshes.size() - 1), WorldTransform(1.0)};
  scene.shapes.push_back(shape);
}

constexpr float kGreyLinear = 0.21586f;  // sRGB 128 decoded

// A white quad facing the camera (+z) with uvs as the quads' (u along +x, v
// down the image) and a uniform normal map of `mapped`, lit by one light from
// `direction`: its brightness is the bent normal's cosine to the light. The
// mesh is placed by `placement`, `copies` times (more than once: stored in
// object space, the others far off to the side).
float normalMappedBrightness(glm::vec3 mapped, glm::vec3 direction, float scale = 1.0f,
                             WorldTransform placement = WorldTransform(1.0), int copies = 1) {
  Scene scene = flatLitScene();
  scene.textures = {{"normal map", {1, 1, {}}, true}};
  glm::vec3 encoded = glm::round((mapped * 0.5f + 0.5f) * 255.0f);
  scene.textures[0].image.rgba = {uint8_t(encoded.x), uint8_t(encoded.y), uint8_t(encoded.z), 255};
  scene.materials[0].diffuseTexture = -1;
  scene.materials[0].diffuseColor = glm::vec3(1.0f);
  scene.materials[0].normalTexture = 0;
  scene.materials[0].normalScale = scale;
  scene.pointLights[0].position = glm::dvec3(glm::normalize(direction)) * 1e6;
  // Counter-clockwise from the camera: its front. (Seen from the back, the
  // whole bent normal turns over, as glTF's double-sided materials do.)
  scene.meshes.push_back(squareMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 2, 1}, {0, 3, 2}}));
  for (int copy = 0; copy < copies; ++copy) {
    Shape shape;
    shape.geometry = MeshInstance{
        0, glm::translate(WorldTransform(1.0), glm::dvec3(100.0 * copy, 0, 0)) * placement};
    scene.shapes.push_back(shape);
  }
  return renderedAt(render(scene), 0.5f, 0.5f).x;
}

// Mean colour of the pixels in [u0, u1) x [v0, v1) of the image.
glm::vec3 meanOver(const ImageF& image, float u0, float v0, float u1, float v1) {
  glm::dvec3 sum(0.0);
  size_t count = 0;
  for (auto y = uint32_t(v0 * float(image.height)); y < uint32_t(v1 * float(image.height)); ++y) {
    for (auto x = uint32_t(u0 * float(image.width)); x < uint32_t(u1 * float(image.width)); ++x) {
      const float* p = image.pixel(x, y);
      sum += glm::dvec3(p[0], p[1], p[2]);
      ++count;
    }
  }
  return glm::vec3(sum / double(count));
}

// Alpha cutouts: the flat-lit square (the light at the camera) in red, its
// texture's left half opaque and its right half clear (alpha 0), a MASK
// material, in front of a green square twice its size at z = -1. `copies`
// places the front square more than once (object space, the other copies
// far off to the side).
Scene cutoutScene(int copies = 1) {
  Scene scene = flatLitScene();
  scene.textures = {
      {"half clear", {4, 1, {255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 0, 255, 0, 0, 0}}}};
  Material& front = scene.materials[0];
  front.textureTintedByColor = true;
  front.diffuseColor = glm::vec3(1.0f);
  front.alphaMode = Material::Alpha::Mask;
  front.alphaTexture = 0;
  Material back;
  back.diffuseColor = {0, 1, 0};
  scene.materials.push_back(back);
  scene.meshes.push_back(squareMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  for (int copy = 0; copy < copies; ++copy) {
    Shape shape;
    shape.geometry =
        MeshInstance{0, glm::translate(WorldTransform(1.0), glm::dvec3(100.0 * copy, 0, 0))};
    scene.shapes.push_back(shape);
  }
  addMesh(scene, squareMesh({}));
  scene.shapes.back().material = 1;
  scene.shapes.back().geometry = MeshInstance{
      1,
      glm::scale(glm::translate(WorldTransform(1.0), glm::dvec3(0, 0, -1)), glm::dvec3(2, 2, 1))};
  return scene;
}

// A glass pane (material 0: index 1, so no Fresnel reflection and no
// bending; kd and ks 0) at z = 0 covering `paneRight` (x from -1.1 to it),
// before a lit square of colour `behind` (material 1) at z = -1.
Scene glassPaneScene(double paneRight, glm::vec3 behind) {
  Scene scene = flatLitScene();
  Material& glass = scene.materials[0];
  glass.diffuseTexture = -1;
  glass.kd = 0.0f;
  glass.ks = 0.0f;
  glass.transmission = 1.0f;
  glass.ior = 1.0f;
  Material square;
  square.diffuseColor = behind;
  scene.materials.push_back(square);
  Shape pane;
  pane.geometry = Quad{{-1.1, 1.1, 0}, {paneRight, 1.1, 0}, {paneRight, -1.1, 0}, {-1.1, -1.1, 0}};
  scene.shapes.push_back(pane);
  Shape back;
  back.geometry = Quad{{-2, 2, -1}, {2, 2, -1}, {2, -2, -1}, {-2, -2, -1}};
  back.material = 1;
  scene.shapes.push_back(back);
  return scene;
}

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
    addMesh(scene, squareMesh({{0, 0}, {2, 0}, {2, 2}, {0, 2}}));
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

  TEST_CASE("normal maps: x along u, y up the image, z out; texels are data; scale") {
    const glm::vec3 towardsU(0.6f, 0.0f, 0.8f);  // the map's normal, tilted along +x
    // 8-bit encoding moves the normal by up to 1/255.
    CHECK(normalMappedBrightness(towardsU, {0.6f, 0.0f, 0.8f}) ==
          doctest::Approx(1.0).epsilon(0.01));
    CHECK(normalMappedBrightness(towardsU, {0.0f, 0.0f, 1.0f}) ==
          doctest::Approx(0.8).epsilon(0.01));
    CHECK(normalMappedBrightness(towardsU, {-0.6f, 0.0f, 0.8f}) ==
          doctest::Approx(0.28).epsilon(0.03));
    // +y of the map is up in the image: against v, along +y here.
    CHECK(normalMappedBrightness({0.0f, 0.6f, 0.8f}, {0.0f, 0.6f, 0.8f}) ==
          doctest::Approx(1.0).epsilon(0.01));
    CHECK(normalMappedBrightness({0.0f, 0.6f, 0.8f}, {0.0f, -0.6f, 0.8f}) ==
          doctest::Approx(0.28).epsilon(0.03));
    // Scale 0.5 halves x and y before normalising: (0.3, 0, 0.8) / 0.854.
    CHECK(normalMappedBrightness(towardsU, {0.0f, 0.0f, 1.0f}, 0.5f) ==
          doctest::Approx(0.937).epsilon(0.01));
    // The flat normal (0, 0, 1) changes nothing.
    CHECK(normalMappedBrightness({0.0f, 0.0f, 1.0f}, {0.6f, 0.0f, 0.8f}) ==
          doctest::Approx(0.8).epsilon(0.01));
  }

  TEST_CASE("normal maps on mirrored meshes follow the mirrored texture, stored once or shared") {
    // Mirrored in x: u runs along -x, and so does the map's tilt.
    const WorldTransform mirror = glm::scale(WorldTransform(1.0), glm::dvec3(-1, 1, 1));
    const glm::vec3 towardsU(0.6f, 0.0f, 0.8f);
    for (int copies : {1, 2}) {  // in world space, or in object space with a normal matrix
      CAPTURE(copies);
      CHECK(normalMappedBrightness(towardsU, {-0.6f, 0.0f, 0.8f}, 1.0f, mirror, copies) ==
            doctest::Approx(1.0).epsilon(0.01));
      CHECK(normalMappedBrightness(towardsU, {0.6f, 0.0f, 0.8f}, 1.0f, mirror, copies) ==
            doctest::Approx(0.28).epsilon(0.03));
      CHECK(normalMappedBrightness(towardsU, {0.6f, 0.0f, 0.8f}, 1.0f, WorldTransform(1.0),
                                   copies) == doctest::Approx(1.0).epsilon(0.01));
    }
  }

  TEST_CASE("a glow shows its colour times its texture, unlit, and lights nothing") {
    Scene scene = flatLitScene();
    scene.pointLights[0].diffuseIntensity = glm::vec3(0.0f);  // nothing lit
    scene.materials[0].diffuseTexture = -1;
    scene.materials[0].glow = {1.0f, 0.5f, 1.0f};
    scene.materials[0].glowTexture = 0;
    Shape quad;
    quad.geometry = Quad{{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
    scene.shapes.push_back(quad);
    // A white sphere beside the quad, in front of it: it would be lit if the glow were a light.
    Material white;
    white.diffuseColor = glm::vec3(1.0f);
    scene.materials.push_back(white);
    Shape sphere;
    sphere.geometry = Sphere{{0.5, 0.5, 0.5}, 0.2f};
    sphere.material = 1;
    scene.shapes.push_back(sphere);
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.25f), {1, 0, 0});                       // red texel
    checkColor(renderedAt(image, 0.75f, 0.75f), {0.21586f, 0.10793f, 0.21586f});  // grey x glow
    checkColor(renderedAt(image, 0.25f, 0.75f), {0, 0, 1});                       // blue
    checkColor(renderedAt(image, 0.75f, 0.25f), {0, 0, 0});  // the sphere: unlit
    // Without a texture (glTF's unlit materials without one): the colour alone.
    scene.materials[0].glowTexture = -1;
    checkColor(renderedAt(render(scene), 0.25f, 0.75f), {1.0f, 0.5f, 1.0f});
  }

  TEST_CASE("vertex colours multiply the textured colour, interpolated across the faces") {
    Scene scene = flatLitScene();
    scene.materials[0].diffuseColor = {0.5f, 0.5f, 0.5f};
    scene.materials[0].textureTintedByColor = true;
    TriangleMesh mesh = squareMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    mesh.colors = {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, {1, 1, 0}};  // yellow
    addMesh(scene, mesh);
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

  TEST_CASE("an unlit glow is multiplied by the vertex colours, an emissive glow is not") {
    Scene scene = flatLitScene();
    scene.pointLights.clear();  // a glow shows its colour without lights
    scene.textures.clear();
    Material& material = scene.materials[0];
    material.diffuseTexture = -1;
    material.kd = 0.0f;
    material.glow = {1.0f, 0.5f, 1.0f};
    material.glowTimesVertexColors = true;  // glTF KHR_materials_unlit
    TriangleMesh mesh = squareMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    mesh.colors = {{1, 0, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}};  // red left, blue right
    addMesh(scene, mesh);
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.05f, 0.5f), {0.95f, 0, 0.05f});
    checkColor(renderedAt(image, 0.5f, 0.3f), {0.5f, 0, 0.5f});
    checkColor(renderedAt(image, 0.95f, 0.7f), {0.05f, 0, 0.95f});
    material.glowTimesVertexColors = false;  // an emissive glow: its colour alone
    checkColor(renderedAt(render(scene), 0.5f, 0.3f), {1.0f, 0.5f, 1.0f});
  }

  TEST_CASE("metallic-roughness textures: each texel's terms, mirrors tinted by the base colour") {
    // A mesh quad of a glTF-like material over a white background, unlit: a
    // texel of smooth metal (left) mirrors the background tinted by the
    // red base colour; one of rough dielectric (right) reflects nothing and,
    // unlit, stays black. The texture's mean would make both halves alike.
    Scene scene = flatLitScene();
    scene.pointLights.clear();
    scene.backgroundColor = glm::vec3(1.0f);
    // Two texels of each, so that bilinear filtering has whole texels to show.
    scene.textures = {{"metal rough",
                       {4, 1, {0, 0, 255, 255, 0, 0, 255, 255, 0, 255, 0, 255, 0, 255, 0, 255}},
                       true}};
    Material& material = scene.materials[0];
    material.diffuseTexture = -1;
    material.diffuseColor = {1, 0, 0};
    material.metalRoughTexture = 0;
    material.metallic = 1.0f;
    material.roughness = 1.0f;
    material.reflectivity = 0.125f;  // the mean's: m (1 - r)^2 at m = r = 0.5
    material.tintedMirror = true;
    scene.settings.maxBounces = 1;
    addMesh(scene, squareMesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 2, 1}, {0, 3, 2}}));
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.5f), {1, 0, 0});
    checkColor(renderedAt(image, 0.75f, 0.5f), {0, 0, 0});
    // Untinted (the coursework files' mirrors): the background as it is.
    material.tintedMirror = false;
    checkColor(renderedAt(render(scene), 0.25f, 0.5f), {1, 1, 1});
  }

  TEST_CASE("glTF glass tints the light through it, shadow rays' too, but not its reflection") {
    // A pane of index 1 (no Fresnel reflection, no bending) over the left
    // half of a white lit square, the light behind the camera: seen through
    // the pane, the square takes the pane's colour twice, once on the camera
    // ray's way and once on the shadow ray's. The right half is as it is.
    Scene scene = glassPaneScene(0.0, glm::vec3(1.0f));
    scene.materials[0].diffuseColor = {1.0f, 0.5f, 0.25f};
    scene.materials[0].tintedTransmission = true;
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.5f), {1.0f, 0.25f, 0.0625f});
    checkColor(renderedAt(image, 0.75f, 0.5f), {1, 1, 1});
    // Coursework glass lets every colour through.
    scene.materials[0].tintedTransmission = false;
    checkColor(renderedAt(render(scene), 0.25f, 0.5f), {1, 1, 1});
    // Of index 1.5 the pane reflects a share of the white background behind
    // the camera untinted, which the camera ray sees beside the tinted light.
    scene.materials[0].tintedTransmission = true;
    scene.materials[0].ior = 1.5f;
    scene.backgroundColor = glm::vec3(1.0f);
    glm::vec3 seen = renderedAt(render(scene), 0.25f, 0.5f);
    const float reflected = 0.04f;  // ((1.5 - 1) / (1.5 + 1))^2 at normal incidence
    CAPTURE(seen.x);
    CAPTURE(seen.z);
    // Blue: reflection 0.04 plus 0.96^2 (two crossings of the light) times
    // 0.0625 (the tint twice) times the lit square.
    CHECK(seen.z == doctest::Approx(reflected + 0.96f * 0.96f * 0.0625f).epsilon(0.02));
  }

  TEST_CASE("a transmission texture: glass where its red is 1, the diffuse base colour where 0") {
    // A pane over a lit green square: its left half's texels (red 1) let
    // everything through, its right half's (red 0) leave a diffuse red
    // surface (kd = 1 - transmission, as glTF's dielectric). Without the
    // texture the whole pane is glass.
    Scene scene = glassPaneScene(1.1, {0, 1, 0});
    scene.textures = {{"transmission",
                       {4, 1, {255, 0, 0, 255, 255, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255}},
                       true}};
    Material& pane = scene.materials[0];
    pane.diffuseColor = {1, 0, 0};  // kd stays the factor's: (1 - metallic)(1 - transmission)
    pane.transmissionTexture = 0;
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.25f, 0.5f), {0, 1, 0});
    checkColor(renderedAt(image, 0.75f, 0.5f), {1, 0, 0});
    scene.materials[0].transmissionTexture = -1;
    checkColor(renderedAt(render(scene), 0.75f, 0.5f), {0, 1, 0});
  }

  TEST_CASE("a thin wall of glass lets light through unbent, a solid bends it") {
    // A glass ball (index 1.5) in front of the quadrant texture, seen off its
    // centre, where a solid ball's refraction bends the view far aside: as a
    // thin wall (glTF transmission without a volume) the ball shows the red
    // quadrant behind it, dimmed by the Fresnel reflections of its four
    // crossings (two of the camera ray, two of the shadow ray).
    Scene scene = flatLitScene();
    scene.settings.maxBounces = 4;
    Material glass;
    glass.kd = 0.0f;
    glass.ks = 0.0f;
    glass.transmission = 1.0f;
    glass.ior = 1.5f;
    glass.thinWalled = true;
    scene.materials.push_back(glass);
    Shape back;  // at z = -5, its red texel's centre behind the pixel at (0.2, 0.2)
    back.geometry = Quad{{-1.2, 1.2, -5}, {1.2, 1.2, -5}, {1.2, -1.2, -5}, {-1.2, -1.2, -5}};
    scene.shapes.push_back(back);
    Shape ball;
    ball.geometry = Sphere{{0, 0, 0}, 0.95f};
    ball.material = 1;
    scene.shapes.push_back(ball);
    glm::vec3 thin = renderedAt(render(scene), 0.2f, 0.2f);
    CAPTURE(thin.x);
    CAPTURE(thin.y);
    CAPTURE(thin.z);
    CHECK(thin.x > 0.5f);
    CHECK(thin.x < 0.95f);
    CHECK(thin.y < 0.02f);
    CHECK(thin.z < 0.02f);
    scene.materials[1].thinWalled = false;
    glm::vec3 solid = renderedAt(render(scene), 0.2f, 0.2f);
    CAPTURE(solid.x);
    CAPTURE(solid.y);
    CAPTURE(solid.z);
    CHECK(glm::distance(solid, thin) > 0.2f);
  }

  TEST_CASE("alpha cutouts: MASK holes let camera and shadow rays through; BLEND a share") {
    Scene scene = cutoutScene();
    ImageF image = render(scene);
    checkColor(renderedAt(image, 0.2f, 0.5f), {1, 0, 0});
    // The green square behind, lit through the same hole.
    checkColor(renderedAt(image, 0.8f, 0.5f), {0, 1, 0});
    // Opaque everywhere: the red square whole.
    scene.materials[0].alphaMode = Material::Alpha::Opaque;
    checkColor(renderedAt(render(scene), 0.8f, 0.5f), {1, 0, 0});
    // A cutoff above the texture's alpha: all hole. BLEND without a texture:
    // a quarter of the camera rays meet the red square, and of the rest, the
    // shadow rays of three quarters pass it to light the green one.
    scene.materials[0].alphaMode = Material::Alpha::Mask;
    scene.materials[0].alphaCutoff = 1.5f;
    checkColor(renderedAt(render(scene), 0.2f, 0.5f), {0, 1, 0});
    scene.materials[0].alphaMode = Material::Alpha::Blend;
    scene.materials[0].alphaTexture = -1;
    scene.materials[0].alphaFactor = 0.25f;
    RenderOptions options;
    options.samplesPerPixel = 64;
    glm::vec3 blended = meanOver(test::render(scene, options), 0.25f, 0.25f, 0.75f, 0.75f);
    CAPTURE(blended.x);
    CAPTURE(blended.y);
    CHECK(blended.x == doctest::Approx(0.25).epsilon(0.03));
    CHECK(blended.y == doctest::Approx(0.75 * 0.75).epsilon(0.03));
    CHECK(blended.z == 0.0f);
  }

  TEST_CASE("alpha cutouts: ray queries give the BVH's image" * test::needsRayQueries()) {
    for (int copies : {1, 2}) {  // in world space, then in object space
      CAPTURE(copies);
      Scene scene = cutoutScene(copies);
      RenderOptions options;
      options.samplesPerPixel = 1;
      ImageF bvh = test::render(scene, options);
      options.accel = AccelKind::Hardware;
      ImageF hardware = test::render(scene, options);
      checkColor(renderedAt(hardware, 0.8f, 0.5f), {0, 1, 0});
      glm::vec3 difference = meanOver(bvh, 0, 0, 1, 1) - meanOver(hardware, 0, 0, 1, 1);
      CHECK(glm::all(glm::lessThan(glm::abs(difference), glm::vec3(1e-4f))));
    }
  }

  TEST_CASE("texture samplers: repeat, clamp to the edge, mirror; nearest texel or bilinear") {
    // Texels red, red, green, green over u from -0.5 (left edge) to 1.5
    // (right edge): image x 0.1 reads u = -0.3, 0.9 reads u = 1.3.
    Scene scene = flatLitScene();
    scene.textures = {{"red red green green",
                       {4, 1, {255, 0, 0, 255, 255, 0, 0, 255, 0, 255, 0, 255, 0, 255, 0, 255}}}};
    addMesh(scene, squareMesh({{-0.5f, 0}, {1.5f, 0}, {1.5f, 1}, {-0.5f, 1}}));
    using Wrap = TextureSampling::Wrap;
    struct Expected {
      Wrap wrap;
      glm::vec3 left, right;
    };
    const glm::vec3 red(1, 0, 0), green(0, 1, 0);
    for (const Expected& expected :
         {Expected{Wrap::Repeat, green, red}, Expected{Wrap::Clamp, red, green},
          Expected{Wrap::Mirror, red, green}}) {
      CAPTURE(int(expected.wrap));
      scene.textures[0].sampling.wrapU = expected.wrap;
      ImageF image = render(scene);
      checkColor(renderedAt(image, 0.1f, 0.5f), expected.left);
      checkColor(renderedAt(image, 0.9f, 0.5f), expected.right);
    }
    // u = 0.45, between texels 1 and 2: mixed, or texel 1 alone.
    scene.textures[0].sampling = {};
    checkColor(renderedAt(render(scene), 0.475f, 0.5f), {0.7f, 0.3f, 0});
    scene.textures[0].sampling.nearest = true;
    checkColor(renderedAt(render(scene), 0.475f, 0.5f), red);
  }
}
