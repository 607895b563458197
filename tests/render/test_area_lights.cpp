// Area lights, the mixed mode's distributed bounces and the path tracer,
// against answers known in advance: limits, quadratures, furnaces, and the
// two modes agreeing where they must.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

constexpr float kPi = glm::pi<float>();

ImageF renderScene(const Scene& scene, uint32_t spp, SamplerKind sampler = SamplerKind::Sobol) {
  RenderOptions options;
  options.samplesPerPixel = spp;
  options.sampler = sampler;
  return test::render(scene, options);
}

glm::vec3 pixel(const ImageF& image, uint32_t x, uint32_t y) {
  const float* p = image.pixel(x, y);
  return {p[0], p[1], p[2]};
}

// Mean of one channel over a square of pixels around (x, y).
float meanAround(const ImageF& image, uint32_t x, uint32_t y, uint32_t half, int channel = 0) {
  double sum = 0;
  uint32_t count = 0;
  for (uint32_t j = y - half; j <= y + half; ++j) {
    for (uint32_t i = x - half; i <= x + half; ++i) {
      sum += image.pixel(i, j)[channel];
      ++count;
    }
  }
  return float(sum / count);
}

uint32_t addShape(Scene& scene, Geometry geometry, const Material& material) {
  scene.materials.push_back(material);
  Shape shape;
  shape.geometry = geometry;
  shape.material = uint32_t(scene.materials.size() - 1);
  scene.shapes.push_back(std::move(shape));
  return uint32_t(scene.shapes.size() - 1);
}

void addAreaLight(Scene& scene, Geometry geometry, float intensity, uint32_t samples) {
  Material emitter = test::diffuse(glm::vec3(0), 0);
  AreaLight light;
  light.shape = addShape(scene, geometry, emitter);
  light.diffuseIntensity = light.specularIntensity = glm::vec3(intensity);
  light.samples = samples;
  scene.areaLights.push_back(light);
}

// A white diffuse wall in the plane z = 0 facing a camera on +z, family A
// (lights fall off as I / (4 pi d^2)) with the linear shading model.
Scene wallScene(uint32_t size) {
  Scene scene;
  scene.conventions = Conventions::CourseworkA;
  scene.settings.maxBounces = 4;
  scene.settings.branchBailout = 0.0f;  // analytic values: every light sample traced
  scene.camera.width = scene.camera.height = size;
  scene.camera.position = {0, 0, 5};
  scene.camera.forward = {0, 0, -1};
  scene.camera.fovYDegrees = 40;
  addShape(scene, Quad{{-20, -20, 0}, {20, -20, 0}, {20, 20, 0}, {-20, 20, 0}},
           test::diffuse(glm::vec3(1)));
  return scene;
}

// A 2x1 quad light facing down over the wall scene's plane.
void addOverheadQuadLight(Scene& scene) {
  addAreaLight(scene, Quad{{-1, 2.5f, 0.5f}, {1, 2.5f, 0.5f}, {1, 2.5f, 1.5f}, {-1, 2.5f, 1.5f}},
               8.0f, 2);
}

// A lamp sphere above the floor, out of view; the camera looks down at the
// floor under it from the side (pixel 24, 24). addGlassBall puts a ball
// between them, which focuses the lamp into a caustic there.
Scene causticStage() {
  Scene scene = wallScene(48);
  scene.camera.position = {0, -4, 3};
  scene.camera.forward = glm::normalize(glm::vec3(0, 4, -3));
  scene.camera.up = {0, 0, 1};
  scene.settings.maxBounces = 6;
  addAreaLight(scene, Sphere{{0, 0, 3}, 0.3f}, 40.0f, 1);
  return scene;
}

void addGlassBall(Scene& scene) {
  Material glass = test::diffuse(glm::vec3(0), 0);
  glass.transmission = 1;
  glass.ior = 1.5f;
  addShape(scene, Sphere{{0, 0, 1.1f}, 0.5f}, glass);
}

RenderOptions standardShading(uint32_t spp) {
  RenderOptions options;
  options.samplesPerPixel = spp;
  options.sampler = SamplerKind::Sobol;
  options.shading = ShadingModel::Standard;
  return options;
}

double maxRelativeDifference(const ImageF& a, const ImageF& b, float floor) {
  double worst = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    double reference = std::max(std::abs(double(b.rgba[i])), double(floor));
    worst = std::max(worst, std::abs(double(a.rgba[i]) - b.rgba[i]) / reference);
  }
  return worst;
}

}  // namespace

TEST_SUITE("area lights") {
  TEST_CASE("a tiny quad light and a lamp sphere light like the point light at their centre") {
    // The lights sit above the view, so only their light is seen.
    const WorldPoint centre{0.3, 2.5, 1.5};
    Scene point = wallScene(48);
    point.pointLights.push_back({centre, glm::vec3(3), glm::vec3(3)});
    const ImageF expected = test::render(point, standardShading(16));

    Scene tinyQuad = wallScene(48);
    const double h = 5e-4;
    addAreaLight(tinyQuad,
                 Quad{centre + glm::dvec3(-h, 0, -h), centre + glm::dvec3(h, 0, -h),
                      centre + glm::dvec3(h, 0, h), centre + glm::dvec3(-h, 0, h)},
                 3.0f, 1);
    CHECK(maxRelativeDifference(test::render(tinyQuad, standardShading(16)), expected, 1e-3f) <
          2e-3);

    // A Lambertian sphere wholly above a surface lights it exactly like a
    // point at its centre, however large it is.
    Scene lamp = wallScene(48);
    addAreaLight(lamp, Sphere{centre, 0.5f}, 3.0f, 4);
    CHECK(maxRelativeDifference(test::render(lamp, standardShading(64)), expected, 1e-3f) < 0.02);
  }

  TEST_CASE("a large quad light gives the irradiance of its points' quadrature") {
    // A vertical 2 x 1 light above the view, facing nothing in particular:
    // its points shine in all directions, I / A each.
    const float intensity = 8.0f;
    Scene scene = wallScene(33);
    addAreaLight(scene, Quad{{-1, 2.5f, 0.5f}, {1, 2.5f, 0.5f}, {1, 2.5f, 1.5f}, {-1, 2.5f, 1.5f}},
                 intensity, 4);
    const ImageF image = test::render(scene, standardShading(256));
    // The centre pixel sees the wall at the origin (normal +z).
    double sum = 0;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        double x = -1 + 2 * (i + 0.5) / n;
        double z = 0.5 + (j + 0.5) / n;
        double d2 = x * x + 2.5 * 2.5 + z * z;
        sum += (z / std::sqrt(d2)) / d2;  // cos at the wall / d^2
      }
    }
    double area = 2.0;
    double expected = intensity / (4 * kPi) * sum * (area / (double(n) * n)) / area;
    CHECK(meanAround(image, 16, 16, 1) == doctest::Approx(expected).epsilon(0.01).scale(0));

    // Lambertian, the same power: radiance 2 pi I lightScale / A from each
    // face, so each point sends 2 |cos| times as much (normal along y).
    scene.areaLights[0].profile = EmissionProfile::Lambertian;
    const ImageF lambertian = test::render(scene, standardShading(256));
    sum = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        double x = -1 + 2 * (i + 0.5) / n;
        double z = 0.5 + (j + 0.5) / n;
        double d2 = x * x + 2.5 * 2.5 + z * z;
        sum += 2 * (2.5 / std::sqrt(d2)) * (z / std::sqrt(d2)) / d2;
      }
    }
    expected = intensity / (4 * kPi) * sum / (double(n) * n);
    CHECK(meanAround(lambertian, 16, 16, 1) == doctest::Approx(expected).epsilon(0.01).scale(0));
  }

  TEST_CASE("an area light casts a penumbra, a point light a sharp shadow") {
    // A black ball between the wall and a light above the view.
    // Each pixel against the same scene without the ball.
    const auto shadowBand = [](Scene scene) {
      const ImageF image = test::render(scene, standardShading(64));
      scene.materials[scene.shapes[1].material] = test::diffuse(glm::vec3(0), 0);
      scene.shapes[1].geometry = Sphere{{0, 0, -5}, 0.1f};  // out of the way, behind the wall
      const ImageF unshadowed = test::render(scene, standardShading(64));
      uint32_t partial = 0;
      uint32_t dark = 0;
      for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
          float ratio = pixel(image, x, y).x / pixel(unshadowed, x, y).x;
          partial += ratio > 0.1f && ratio < 0.9f;
          dark += ratio <= 0.1f;
        }
      }
      return std::pair{partial, dark};
    };
    Scene point = wallScene(64);
    addShape(point, Sphere{{0, 0, 1}, 0.4f}, test::diffuse(glm::vec3(0), 0));
    Scene area = point;
    point.pointLights.push_back({{0, 2, 2.5f}, glm::vec3(40), glm::vec3(40)});
    addAreaLight(area, Quad{{-0.5f, 2, 2}, {0.5f, 2, 2}, {0.5f, 2, 3}, {-0.5f, 2, 3}}, 40.0f, 8);
    // Plain variables: clang 14 cannot capture structured bindings (CAPTURE).
    const std::pair<uint32_t, uint32_t> pointBand = shadowBand(point);
    const std::pair<uint32_t, uint32_t> areaBand = shadowBand(area);
    const uint32_t pointPartial = pointBand.first;
    const uint32_t pointDark = pointBand.second;
    const uint32_t areaPartial = areaBand.first;
    const uint32_t areaDark = areaBand.second;
    CAPTURE(pointPartial);
    CAPTURE(pointDark);
    CAPTURE(areaPartial);
    CAPTURE(areaDark);
    CHECK(pointDark > 200);
    CHECK(areaPartial > 3 * pointPartial);
  }

  TEST_CASE("the camera and mirrors see a light's surface at its radiance") {
    // A quad light facing the camera, and behind the camera a second
    // camera's view of the same light in a perfect mirror.
    Scene direct = wallScene(32);
    const float intensity = 2.0f;
    const float side = 1.0f;
    addAreaLight(direct,
                 Quad{{-side / 2, -side / 2, 2},
                      {side / 2, -side / 2, 2},
                      {side / 2, side / 2, 2},
                      {-side / 2, side / 2, 2}},
                 intensity, 1);
    // Seen head on: pi * I * lightScale / A (README "Area lights"), twice
    // that when Lambertian.
    const float expected = kPi * intensity / (4 * kPi) / (side * side);
    CHECK(pixel(test::render(direct, standardShading(4)), 16, 16).x ==
          doctest::Approx(expected).epsilon(1e-3).scale(0));
    direct.areaLights[0].profile = EmissionProfile::Lambertian;
    CHECK(pixel(test::render(direct, standardShading(4)), 16, 16).x ==
          doctest::Approx(2 * expected).epsilon(1e-3).scale(0));

    Scene mirrored = wallScene(32);
    Material mirror = test::diffuse(glm::vec3(0), 0);
    mirror.reflectivity = 1;
    mirrored.materials[mirrored.shapes[0].material] = mirror;
    addAreaLight(mirrored,
                 Quad{{-side / 2, -side / 2, 6},
                      {side / 2, -side / 2, 6},
                      {side / 2, side / 2, 6},
                      {-side / 2, side / 2, 6}},
                 intensity, 1);
    CHECK(pixel(test::render(mirrored, standardShading(4)), 16, 16).x ==
          doctest::Approx(expected).epsilon(1e-3).scale(0));
  }
}

TEST_SUITE("light splitting") {
  TEST_CASE("replicas as asked, or four area-light shadow rays a hit in adaptive renders") {
    Scene scene = test::projectScene("study-arealight.json");  // one light, one sample
    auto replicas = [&](bool adaptive) {
      return detectFeatures(scene, flattenScene(scene), adaptive).lightReplicas;
    };
    CHECK(replicas(false) == 1);
    CHECK(replicas(true) == 4);
    setAreaLightSamples(scene, 3);
    CHECK(replicas(true) == 2);
    setAreaLightSamples(scene, 4);
    CHECK(replicas(true) == 1);
    scene.settings.lightSplit = 3;
    CHECK(replicas(false) == 3);
    CHECK(replicas(true) == 3);
    ShaderDefines defines = detectFeatures(scene, flattenScene(scene)).defines();
    CHECK(std::count(defines.begin(), defines.end(),
                     std::pair<std::string, std::string>("RT_LIGHT_REPLICAS", "3u")) == 1);
    scene.settings.lightSplit = 1;
    CHECK(replicas(true) == 1);
    scene.settings.lightSplit = 0;  // automatic
    setAreaLightSamples(scene, 1);
    REQUIRE(replicas(true) == 4);
    scene.settings.mode = RenderMode::PathTracer;  // indirect light is the noise
    CHECK(replicas(true) == 1);
    scene.settings.mode = RenderMode::Phong;
    scene.settings.distributedBounces = 1;
    CHECK(replicas(true) == 1);

    Scene unlit = wallScene(8);  // no area light: nothing to split
    unlit.settings.lightSplit = 3;
    CHECK(detectFeatures(unlit, flattenScene(unlit), true).lightReplicas == 1);
  }

  TEST_CASE("a scene that nothing lights is said to render black") {
    const auto saysBlack = [](const Scene& scene) {
      const std::vector<std::string> warnings = flattenScene(scene).warnings;
      return std::any_of(warnings.begin(), warnings.end(), [](const std::string& warning) {
        return warning.find("nothing lights the scene") != std::string::npos;
      });
    };
    Scene scene = wallScene(8);
    CHECK(saysBlack(scene));
    scene.settings.mode = RenderMode::PathTracer;
    CHECK(saysBlack(scene));
    scene.settings.mode = RenderMode::Binary;  // hits drawn in one colour: no light needed
    CHECK_FALSE(saysBlack(scene));

    Scene lit = wallScene(8);
    addOverheadQuadLight(lit);
    CHECK_FALSE(saysBlack(lit));
    lit = wallScene(8);
    lit.pointLights.push_back({});
    CHECK_FALSE(saysBlack(lit));
    lit = wallScene(8);
    lit.backgroundColor = glm::vec3(0, 0, 0.1f);  // seen where rays miss, and lights the paths
    CHECK_FALSE(saysBlack(lit));
    lit = wallScene(8);
    lit.conventions = Conventions::CourseworkB;  // its ambient term lights every hit
    CHECK_FALSE(saysBlack(lit));
    lit.ambientLight = glm::vec3(0.0f);  // a file's own ambient light of zero replaces it
    CHECK(saysBlack(lit));
  }
}

TEST_SUITE("path tracer and distributed bounces") {
  TEST_CASE("white furnace: a diffuse sphere under a uniform sky reflects its albedo") {
    Scene scene = wallScene(32);
    scene.shapes.clear();
    scene.materials.clear();
    scene.conventions = Conventions::Textbook;
    scene.backgroundColor = glm::vec3(1);
    addShape(scene, Sphere{{0, 0, 0}, 1.0f}, test::diffuse({0.5f, 0.25f, 1.0f}, 0.8f));
    scene.settings.mode = RenderMode::PathTracer;
    scene.settings.maxBounces = 3;
    const ImageF image = renderScene(scene, 64);
    // Every bounce off a convex sphere escapes to the sky: exactly kd * colour.
    for (uint32_t y = 12; y <= 20; ++y) {
      for (uint32_t x = 12; x <= 20; ++x) {
        glm::vec3 value = pixel(image, x, y);
        CHECK(value.x == doctest::Approx(0.4).epsilon(1e-4).scale(0));
        CHECK(value.y == doctest::Approx(0.2).epsilon(1e-4).scale(0));
        CHECK(value.z == doctest::Approx(0.8).epsilon(1e-4).scale(0));
      }
    }
    // Paths of length 0 see only emitted and direct light: none.
    scene.settings.maxBounces = 0;
    CHECK(pixel(renderScene(scene, 4), 16, 16) == glm::vec3(0));
  }

  TEST_CASE("with nothing to bounce off, the path tracer equals the mixed mode's direct light") {
    // A flat wall lit by an area and a point light: every bounce leaves
    // to the black sky or reaches the light, whose emission next-event
    // estimation already counted. Counting it twice would brighten the wall.
    Scene scene = wallScene(32);
    scene.pointLights.push_back({{1, 1, 2}, glm::vec3(4), glm::vec3(4)});
    addOverheadQuadLight(scene);
    const ImageF phong = test::render(scene, standardShading(64));
    scene.settings.mode = RenderMode::PathTracer;
    const ImageF traced = test::render(scene, standardShading(64));
    CHECK(maxRelativeDifference(traced, phong, 1e-3f) < 1e-4);
  }

  TEST_CASE("glass focuses an area light into a caustic only where paths are sampled") {
    const Scene bare = causticStage();
    Scene scene = bare;
    addGlassBall(scene);
    const float lit = meanAround(test::render(bare, standardShading(16)), 24, 24, 1);
    const float whitted = meanAround(test::render(scene, standardShading(16)), 24, 24, 1);
    scene.settings.mode = RenderMode::PathTracer;
    const ImageF traced = test::render(scene, standardShading(512));
    test::savePng(toneMap(traced, ToneMapping{}), "caustic-pathtraced.png");
    const float caustic = meanAround(traced, 24, 24, 1);
    CAPTURE(lit);
    CAPTURE(whitted);
    CAPTURE(caustic);
    // Straight shadow rays through glass can only lose light; the focused
    // paths bring several times the direct light to the spot.
    CHECK(whitted < lit);
    CHECK(whitted > 0.5f * lit);
    CHECK(caustic > 2 * lit);
  }

  TEST_CASE("the firefly clamp bounds light after a diffuse bounce, not direct light") {
    // Direct light only (see above): the clamp has nothing to hold back.
    Scene wall = wallScene(32);
    wall.settings.mode = RenderMode::PathTracer;
    addOverheadQuadLight(wall);
    const ImageF unclamped = test::render(wall, standardShading(16));
    wall.settings.indirectClamp = 1e-4f;
    CHECK(maxRelativeDifference(test::render(wall, standardShading(16)), unclamped, 1e-3f) == 0.0);

    // The caustic above is all light after a diffuse bounce: each sample
    // adds at most two clamped contributions per vertex, plus the sky.
    Scene caustic = causticStage();
    addGlassBall(caustic);
    caustic.settings.mode = RenderMode::PathTracer;
    const float focused = meanAround(test::render(caustic, standardShading(256)), 24, 24, 1);
    caustic.settings.indirectClamp = 1e6f;  // above every contribution: no change
    const float highClamp = meanAround(test::render(caustic, standardShading(256)), 24, 24, 1);
    const float limit = 0.02f;
    caustic.settings.indirectClamp = limit;
    const float clamped = meanAround(test::render(caustic, standardShading(256)), 24, 24, 1);
    CAPTURE(focused);
    CAPTURE(clamped);
    CHECK(highClamp == focused);
    CHECK(clamped > 0.0f);
    CHECK(clamped < 0.5f * focused);
    CHECK(clamped <= float(2 * caustic.settings.maxBounces + 1) * limit);
  }

  TEST_CASE("a distributed diffuse bounce bleeds a wall's colour onto the floor") {
    Scene scene = wallScene(32);
    // A red wall standing on the white one, to the image's right.
    addShape(scene, Quad{{0.5f, -3, 0}, {0.5f, 3, 0}, {0.5f, 3, 3}, {0.5f, -3, 3}},
             test::diffuse({1, 0, 0}));
    scene.pointLights.push_back({{-1, 0, 3}, glm::vec3(30), glm::vec3(30)});
    const ImageF direct = test::render(scene, standardShading(16));
    scene.settings.distributedBounces = 1;
    const ImageF bounced = test::render(scene, standardShading(64));
    const glm::vec3 floorDirect = pixel(direct, 10, 16);
    const glm::vec3 floorBounced = pixel(bounced, 10, 16);
    CHECK(floorDirect.x == doctest::Approx(floorDirect.y));
    CHECK(floorBounced.x > floorBounced.y * 1.05f);
    CHECK(floorBounced.y == doctest::Approx(floorDirect.y).epsilon(0.02).scale(0));
  }

  TEST_CASE("the student renders with area lights and thin lenses match their authors'" *
            test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    const auto folder = shared / "scene-format/student/TsFreddie__RayTracer";
    for (const char* name : {"softshadow", "dof"}) {
      CAPTURE(name);
      const Scene scene = loadJsonScene(folder / "examples" / (std::string(name) + "_test.json"));
      RenderOptions options;
      options.samplesPerPixel = 256;
      options.sampler = scene.settings.sampler;
      const Image8 ours = toneMap(test::render(scene, options), toneMappingFor(scene));
      const Image8 theirs = readImage8(folder / name / "ref.png");
      test::savePng(ours, std::string("student-") + name + ".png");
      CHECK(test::psnr(ours, theirs) > 36.0);
    }
  }
}
