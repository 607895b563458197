// End-to-end renders of small scenes with answers known in advance.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "encode/Conventions.hpp"
#include "encode/SceneBuffers.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "imaging/Merge.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

using namespace rt;

namespace {

// Camera on +z looking at the origin, one point light beside the camera
// (family B conventions: no falloff, unit scale).
Scene baseScene(uint32_t width, uint32_t height) {
  return test::frontStage(width, height, {0, 0, 50}, 0.8f);
}

glm::vec3 pixel(const ImageF& image, uint32_t x, uint32_t y) {
  const float* p = image.pixel(x, y);
  return {p[0], p[1], p[2]};
}

// A black sphere that only mirrors, by `reflectivity`, a white background.
Scene faintMirrorScene(float reflectivity) {
  Scene scene = baseScene(24, 24);
  scene.backgroundColor = glm::vec3(1.0f);
  Material faintMirror = test::diffuse(glm::vec3(0), 0, 0);
  faintMirror.reflectivity = reflectivity;
  test::addSphere(scene, faintMirror);
  return scene;
}

// A grey sphere in binary mode: hits in the hit colour, misses in the background.
Scene binarySphereScene(uint32_t width, uint32_t height) {
  Scene scene = baseScene(width, height);
  scene.settings.mode = RenderMode::Binary;
  test::addSphere(scene, test::diffuse({0.3f, 0.3f, 0.3f}));
  return scene;
}

bool bitwiseEqual(const ImageF& a, const ImageF& b) {
  return a.rgba.size() == b.rgba.size() &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

bool allFinite(const ImageF& image) {
  for (float v : image.rgba) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

TEST_SUITE("render") {
  TEST_CASE("Blinn-Phong at the sphere's centre matches the analytic value") {
    // Light and eye on the axis: n.l = n.h = 1 at the centre pixel, so
    // L = kd * Cd * I + ks * Cs * I exactly.
    Scene scene = baseScene(101, 101);
    test::addSphere(scene, test::diffuse({0.5f, 0.25f, 1.0f}, 0.6f, 0.3f));
    RenderOptions options;
    options.samplesPerPixel = 1;
    ImageF image = test::render(scene, options);
    glm::vec3 expected = 0.8f * (0.6f * glm::vec3(0.5f, 0.25f, 1.0f) + 0.3f * glm::vec3(1.0f));
    glm::vec3 centre = pixel(image, 50, 50);
    // The jittered sample lands anywhere in the pixel: the normal there is
    // within about 1 degree of the axis, which bounds the error below 1e-3.
    CHECK(glm::all(glm::lessThan(glm::abs(centre - expected), glm::vec3(2e-3f))));
    CHECK(pixel(image, 0, 0) == scene.backgroundColor);
  }

  TEST_CASE("physical conventions: light falls off as I / (4 pi d^2), images are sRGB") {
    // Light and eye on the axis, the light 4 units in front of the sphere:
    // the centre's radiance is (kd Cd + ks Cs) I / (4 pi 4^2).
    Scene scene = test::frontStage(101, 101, {0, 0, 5}, 50.0f);
    test::addSphere(scene, test::diffuse({0.5f, 0.25f, 1.0f}, 0.6f, 0.3f));
    setConventions(scene, Conventions::Physical, "test");
    RenderOptions options;
    options.samplesPerPixel = 1;
    const ImageF image = test::render(scene, options);
    const float falloff = 50.0f / (4.0f * 3.14159265f * 16.0f);
    const glm::vec3 expected =
        falloff * (0.6f * glm::vec3(0.5f, 0.25f, 1.0f) + 0.3f * glm::vec3(1.0f));
    CHECK(glm::all(glm::lessThan(glm::abs(pixel(image, 50, 50) - expected), glm::vec3(2e-3f))));
    CHECK(scene.camera.imageRight == ImageRight::ForwardCrossUp);
    CHECK(toneMappingFor(scene).srgbEncode);
    setConventions(scene, Conventions::CourseworkA, "test");
    CHECK_FALSE(toneMappingFor(scene).srgbEncode);
  }

  TEST_CASE("a perfect mirror sphere shows the background it reflects") {
    Scene scene = baseScene(32, 32);
    Material mirror = test::diffuse(glm::vec3(0), 0, 0);
    mirror.reflectivity = 1;
    test::addSphere(scene, mirror);
    scene.settings.maxBounces = 3;
    RenderOptions options;
    options.samplesPerPixel = 4;
    ImageF image = test::render(scene, options);
    CHECK(glm::all(
        glm::lessThan(glm::abs(pixel(image, 16, 16) - scene.backgroundColor), glm::vec3(1e-6f))));
  }

  TEST_CASE("family B: a full mirror shows only what it reflects, a half mirror half of each") {
    // A bright, shiny sphere: under coursework-b its own light is weighted
    // by 1 - reflectivity; the textbook conventions add it to the reflection.
    auto sphereScene = [](float reflectivity, Conventions conventions) {
      Scene scene = baseScene(32, 32);
      setConventions(scene, conventions, "test");
      Material material = test::diffuse({1.0f, 0.5f, 0.5f}, 0.9f, 0.5f);
      material.reflectivity = reflectivity;
      test::addSphere(scene, material);
      scene.settings.maxBounces = 3;
      return scene;
    };
    RenderOptions options;
    options.samplesPerPixel = 2;
    // At the centre the mirror looks back along the camera ray, at nothing.
    const glm::vec3 background = baseScene(1, 1).backgroundColor;
    glm::vec3 mirror =
        pixel(test::render(sphereScene(1, Conventions::CourseworkB), options), 16, 16);
    CHECK(glm::all(glm::lessThan(glm::abs(mirror - background), glm::vec3(1e-6f))));
    glm::vec3 matte =
        pixel(test::render(sphereScene(0, Conventions::CourseworkB), options), 16, 16);
    glm::vec3 half =
        pixel(test::render(sphereScene(0.5f, Conventions::CourseworkB), options), 16, 16);
    CHECK(glm::all(glm::lessThan(glm::abs(half - 0.5f * (matte + background)), glm::vec3(1e-5f))));
    // The ambient term: 0.4 of the diffuse colour comes on top of the light.
    CHECK(matte.x <= 1.0f);
    CHECK(matte.y > 0.4f * 0.5f);
    glm::vec3 added = pixel(test::render(sphereScene(1, Conventions::Textbook), options), 16, 16);
    CHECK(added.x > background.x + 0.5f);
  }

  TEST_CASE("a scene's ambient light is its colour times the diffuse colour, shadows or not") {
    Scene scene = baseScene(32, 32);
    scene.pointLights.clear();  // ambient light alone
    test::addSphere(scene, test::diffuse({1.0f, 0.5f, 0.0f}, 0.9f, 0.5f));
    RenderOptions options;
    options.samplesPerPixel = 1;
    CHECK(pixel(test::render(scene, options), 16, 16) == glm::vec3(0.0f));
    scene.ambientLight = glm::vec3(0.5f, 0.5f, 1.0f);
    const glm::vec3 lit = pixel(test::render(scene, options), 16, 16);
    CHECK(glm::all(glm::lessThan(glm::abs(lit - glm::vec3(0.5f, 0.25f, 0.0f)), glm::vec3(1e-6f))));
    // It replaces family B's 0.4.
    setConventions(scene, Conventions::CourseworkB, "test");
    const glm::vec3 familyB = pixel(test::render(scene, options), 16, 16);
    CHECK(glm::all(glm::lessThan(glm::abs(familyB - lit), glm::vec3(1e-6f))));
  }

  TEST_CASE("glass with the index of the surrounding air is invisible") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({1, 1, 0}), {0, 0, -3}, 1.5f);
    Scene withGlass = scene;
    Material glass = test::diffuse(glm::vec3(0), 0, 0);
    glass.transmission = 1;
    glass.ior = 1;
    test::addSphere(withGlass, glass, {0, 0, 0}, 1.0f);
    withGlass.settings.maxBounces = 4;
    RenderOptions options;
    options.samplesPerPixel = 2;
    ImageF plain = test::render(scene, options);
    ImageF glassy = test::render(withGlass, options);
    double maxDifference = 0;
    for (size_t i = 0; i < plain.rgba.size(); ++i) {
      maxDifference = std::max(maxDifference, double(std::abs(plain.rgba[i] - glassy.rgba[i])));
    }
    // Only rays that graze the glass within float rounding may differ.
    CHECK(maxDifference < 0.05);
  }

  TEST_CASE("Russian roulette on faint branches keeps the glass scene's image, only noisier") {
    Scene scene = test::projectScene("default.json");
    scene.settings.rouletteWeight = 0.03f;
    RenderOptions options;
    options.width = 80;
    options.height = 60;
    options.samplesPerPixel = 256;
    options.sampler = SamplerKind::Sobol;
    RenderStats rouletteStats, fullStats;
    ImageF roulette = test::render(scene, options, &rouletteStats);
    Scene full = scene;
    full.settings.rouletteWeight = 0.0f;
    ImageF everyBranch = test::render(full, options, &fullStats);
    CHECK(std::abs(rouletteStats.features.rouletteWeight - 0.03f) < 1e-6f);
    CHECK(fullStats.features.rouletteWeight == 0.0f);
    double sumRoulette = 0, sumFull = 0, absoluteDifference = 0;
    for (size_t i = 0; i < roulette.rgba.size(); ++i) {
      if (i % 4 == 3) continue;
      sumRoulette += roulette.rgba[i];
      sumFull += everyBranch.rgba[i];
      absoluteDifference += std::abs(roulette.rgba[i] - everyBranch.rgba[i]);
    }
    // Unbiased: the same mean; the images differ by the roulette's noise only.
    CHECK(sumRoulette == doctest::Approx(sumFull).epsilon(0.005).scale(0));
    CHECK(absoluteDifference / sumFull < 0.02);
    CHECK(roulette.rgba != everyBranch.rgba);  // the roulette did drop branches
  }

  TEST_CASE("Russian roulette reweights the branches it keeps: a faint mirror keeps its value") {
    // A black sphere with a 2% mirror in front of a white background: the
    // mirror rays (weight 0.02, below the roulette's 0.03) survive two times
    // in three and carry 0.03, so the sphere still shows 2% of the white.
    Scene scene = faintMirrorScene(0.02f);
    scene.settings.rouletteWeight = 0.03f;
    RenderOptions options;
    options.samplesPerPixel = 64;
    options.sampler = SamplerKind::Sobol;
    RenderStats stats;
    ImageF image = test::render(scene, options, &stats);
    REQUIRE(stats.features.rouletteWeight > 0.02f);
    double sum = 0;
    for (uint32_t y = 10; y < 14; ++y) {
      for (uint32_t x = 10; x < 14; ++x) sum += pixel(image, x, y).y;
    }
    CHECK(std::abs(sum / 16 - 0.02) < 0.001);  // without the reweighting: 0.0133
  }

  TEST_CASE("the bailout drops ray-tree branches lighter than it, and only those") {
    // A black sphere with a 0.3% mirror before a white background: its
    // mirror rays weigh 0.003, below the default bailout of 1/255.
    Scene scene = faintMirrorScene(0.003f);
    RenderOptions options;
    options.samplesPerPixel = 1;
    auto centre = [&](float bailout) {
      scene.settings.branchBailout = bailout;
      return pixel(test::render(scene, options), 12, 12).y;
    };
    CHECK(centre(1.0f / 255.0f) == 0.0f);
    CHECK(centre(0.0f) == doctest::Approx(0.003f));
    CHECK(centre(0.002f) == doctest::Approx(0.003f));
    // Shown at 4x exposure the same branch moves the image by more than a
    // step: the bailout counts steps of the shown image, 1/255/4 < 0.003.
    options.displayMapping = toneMappingFor(scene);
    options.displayMapping->exposure = 4.0f;
    CHECK(centre(1.0f / 255.0f) == doctest::Approx(0.003f));
    options.displayMapping->exposure = 0.5f;
    CHECK(centre(0.002f) == 0.0f);
    options.displayMapping.reset();
    scene.settings.mode = RenderMode::PathTracer;  // whole-path weights: never dropped at 1/255
    options.samplesPerPixel = 16;
    CHECK(centre(1.0f / 255.0f) == doctest::Approx(0.003f));
  }

  TEST_CASE("a light sample worth less than the bailout is counted at half, untraced") {
    // A faint matte sphere: its one light adds 0.002 at the centre, below
    // 1/255, so with the default bailout the shadow ray is not traced and
    // the light counts at half; with the bailout off, in full.
    Scene scene = baseScene(24, 24);
    test::addSphere(scene, test::diffuse(glm::vec3(1.0f), 0.0025f, 0.0f));
    RenderOptions options;
    options.samplesPerPixel = 1;
    auto centre = [&](float bailout) {
      scene.settings.branchBailout = bailout;
      return pixel(test::render(scene, options), 12, 12).x;
    };
    float traced = centre(0.0f);
    CHECK(traced > 0.0015f);
    CHECK(traced < 0.0025f);
    CHECK(centre(1.0f / 255.0f) == doctest::Approx(0.5f * traced));
  }

  TEST_CASE("Russian roulette is compiled only where mirror or glass rays branch") {
    Scene scene = baseScene(16, 12);
    scene.settings.rouletteWeight = 0.03f;
    test::addSphere(scene, test::diffuse({1, 1, 0}), {0, 0, -3}, 1.5f);
    RenderOptions options;
    options.samplesPerPixel = 1;
    RenderStats matte;
    test::render(scene, options, &matte);
    CHECK(matte.features.rouletteWeight == 0.0f);
    scene.settings.mode = RenderMode::PathTracer;
    Material glass = test::diffuse(glm::vec3(0), 0, 0);
    glass.transmission = 1;
    glass.ior = 1.5f;
    test::addSphere(scene, glass, {0, 0, 0}, 1.0f);
    RenderStats pathTraced;
    test::render(scene, options, &pathTraced);
    CHECK(pathTraced.features.rouletteWeight == 0.0f);  // it follows one branch anyway
  }

  TEST_CASE("binary mode paints hits in one colour and misses in the background colour") {
    Scene scene = binarySphereScene(32, 32);
    RenderOptions options;
    options.samplesPerPixel = 1;
    ImageF image = test::render(scene, options);
    CHECK(pixel(image, 16, 16) == glm::vec3(1, 0, 0));
    CHECK(pixel(image, 0, 0) == scene.backgroundColor);
  }

  TEST_CASE("the benchmarks' ray counter counts every ray traced") {
    // 37x23 is no whole number of 8x8 groups: the lanes past the image's
    // edge must add nothing (the kernel adds a subgroup's rays at once).
    Scene scene = binarySphereScene(37, 23);
    RenderOptions options;
    options.samplesPerPixel = 3;
    options.countRays = true;
    RenderStats binary;
    test::render(scene, options, &binary);
    const uint64_t samples = 37u * 23u * 3u;
    CHECK(binary.raysTraced == samples);  // one primary ray a sample
    scene.settings.mode = RenderMode::Phong;
    RenderStats phong;
    test::render(scene, options, &phong);
    // Plus a shadow ray for each sample whose hit faces the light.
    CHECK(phong.raysTraced > samples + samples / 10);
    CHECK(phong.raysTraced <= 2 * samples);
  }

  TEST_CASE("the odd samples' sums are kept only for an error estimate and change nothing else") {
    Scene scene = baseScene(40, 32);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}, 0.8f, 0.4f));
    RenderOptions options;
    options.samplesPerPixel = 6;
    options.sampler = SamplerKind::Random;  // halves always independent
    RenderStats plain;
    ImageF image = test::render(scene, options, &plain);
    CHECK_FALSE(plain.features.oddSums);
    CHECK(plain.estimatedError.empty());
    options.keepErrorImage = true;  // an error layer (EXR output)
    RenderStats layered;
    CHECK(bitwiseEqual(image, test::render(scene, options, &layered)));
    CHECK(layered.features.oddSums);
    REQUIRE(layered.estimatedError.size() == 40u * 32u);
    // The estimate is a real one: some pixels differ between the halves.
    CHECK(*std::max_element(layered.estimatedError.begin(), layered.estimatedError.end()) > 0.0f);
    options.keepErrorImage = false;
    options.estimateError = true;
    RenderStats estimated;
    test::render(scene, options, &estimated);
    CHECK(estimated.features.oddSums);
    CHECK(estimated.rmseEstimate);
  }

  TEST_CASE("renders are reproducible and do not depend on how samples are split") {
    Scene scene = baseScene(48, 40);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}, 0.8f, 0.4f));
    test::addSphere(scene, test::diffuse({0.2f, 0.5f, 0.9f}), {1.2f, 0.5f, -1}, 0.7f);
    RenderOptions options;
    options.samplesPerPixel = 7;
    options.seed = 42;
    options.secondsPerDispatch = options.secondsPerPass = 10;  // everything in one dispatch
    ImageF whole = test::render(scene, options);
    // One sample a pass and eight rows (one row of workgroups) a dispatch.
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;
    ImageF split = test::render(scene, options);
    CHECK(bitwiseEqual(whole, split));
    options.seed = 43;
    CHECK_FALSE(bitwiseEqual(whole, test::render(scene, options)));
  }

  TEST_CASE("renders of split sample ranges merge into the whole render") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}, 0.8f, 0.4f));
    RenderOptions options;
    options.samplesPerPixel = 7;
    ImageF whole = test::render(scene, options);
    options.firstSample = 0;
    options.endSample = 3;
    ImageF first = test::render(scene, options);
    options.firstSample = 3;
    options.endSample = 7;
    ImageF second = test::render(scene, options);
    CHECK(first.rgba[3] == 3.0f);  // alpha carries the sample count
    ImageF merged = mergeRenders({first, second});
    double worst = 0;
    for (size_t i = 0; i < whole.rgba.size(); ++i) {
      double scale = std::max(1e-3, double(std::abs(whole.rgba[i])));
      worst = std::max(worst, std::abs(double(merged.rgba[i]) - whole.rgba[i]) / scale);
    }
    CHECK(worst < 1e-5);  // float rounding of the per-range sums only
    CHECK_THROWS_AS(mergeRenders({first, ImageF{1, 1, {0, 0, 0, 1}}}), Error);
  }

  TEST_CASE("a render can be stopped between dispatches and keeps its samples") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}));
    RenderOptions options;
    options.samplesPerPixel = 50;
    // Bands of eight rows: passes of 1, 1, 2 and 4 samples take 14
    // dispatches, and the stop comes after the first band of the fifth.
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;
    int polls = 0;
    options.shouldStop = [&] { return ++polls > 15; };
    RenderStats stats;
    ImageF image = Renderer(test::gpu(), test::shaderCompiler()).render(scene, options, {}, &stats);
    CHECK(stats.stoppedEarly);
    CHECK(stats.samplesDone < 50);
    CHECK(image.rgba[3] >= 1.0f);
    CHECK(allFinite(image));
    // Passes double from one sample, so a stop part way through one leaves
    // every pixel at least half the samples of the most sampled one.
    CHECK(stats.samplesDone * 2 >= stats.maxSamples);
    CHECK(stats.maxSamples > stats.samplesDone);  // the stop did come inside a pass
  }

  TEST_CASE("a stop asked for before the first pass ends leaves every pixel one sample") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}));
    RenderOptions options;
    options.samplesPerPixel = 50;
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;  // bands of rows
    options.shouldStop = [] { return true; };  // a --time budget spent while setting up
    RenderStats stats;
    ImageF image = Renderer(test::gpu(), test::shaderCompiler()).render(scene, options, {}, &stats);
    CHECK(stats.stoppedEarly);
    CHECK(stats.samplesDone == 1);
    CHECK(stats.maxSamples == 1);
    for (size_t i = 3; i < image.rgba.size(); i += 4) REQUIRE(image.rgba[i] == 1.0f);
    CHECK(allFinite(image));
  }

  TEST_CASE("a render stopped with passes of one sample keeps pixels within one sample") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}));
    RenderOptions options;
    options.samplesPerPixel = 50;
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;
    options.maxPassSamples = 1;
    int polls = 0;
    options.shouldStop = [&] { return ++polls > 40; };
    RenderStats stats;
    Renderer(test::gpu(), test::shaderCompiler()).render(scene, options, {}, &stats);
    CHECK(stats.stoppedEarly);
    CHECK(stats.maxSamples <= stats.samplesDone + 1);
  }

  TEST_CASE("the image does not depend on how many samples a pass adds") {
    Scene scene = baseScene(40, 30);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}, 0.8f, 0.4f));
    RenderOptions options;
    options.samplesPerPixel = 23;
    // Bands of rows, passes 1, 1, 2, 4, 8, 7.
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;
    ImageF doubling = test::render(scene, options);
    options.maxPassSamples = 1;
    CHECK(bitwiseEqual(doubling, test::render(scene, options)));
    options.maxPassSamples = 64;
    // After the first pass, one of 22 samples.
    options.secondsPerDispatch = options.secondsPerPass = 10.0;
    CHECK(bitwiseEqual(doubling, test::render(scene, options)));
  }

  TEST_CASE("thin lens: aperture 0 is the pinhole image; an open lens blurs off the focal plane") {
    Scene scene = baseScene(48, 36);
    test::addSphere(scene, test::diffuse({0.9f, 0.5f, 0.2f}));  // at distance 5
    test::addSphere(scene, test::diffuse({0.2f, 0.5f, 0.9f}), {1.5f, 0.5f, -5},
                    1.0f);  // at distance 10
    RenderOptions options;
    options.samplesPerPixel = 16;
    ImageF pinhole = test::render(scene, options);
    scene.camera.type = CameraType::ThinLens;
    scene.camera.apertureRadius = 0.0f;
    scene.camera.focusDistance = 5.0f;
    CHECK(bitwiseEqual(pinhole, test::render(scene, options)));
    scene.camera.apertureRadius = 0.3f;
    ImageF lens = test::render(scene, options);
    // The near sphere's centre (in focus) is unchanged; the far sphere's
    // silhouette (out of focus) is smeared.
    double nearChange = glm::length(pixel(lens, 24, 18) - pixel(pinhole, 24, 18));
    double farChange = 0;
    for (uint32_t x = 30; x < 48; ++x) {
      for (uint32_t y = 0; y < 36; ++y)
        farChange += glm::length(pixel(lens, x, y) - pixel(pinhole, x, y));
    }
    CHECK(nearChange < 0.02);
    CHECK(farChange > 1.0);
  }

  TEST_CASE("both samplers converge to the same image") {
    Scene scene = baseScene(24, 24);
    test::addSphere(scene, test::diffuse({0.9f, 0.9f, 0.9f}));
    RenderOptions options;
    options.samplesPerPixel = 64;
    options.sampler = SamplerKind::Random;
    ImageF random = test::render(scene, options);
    options.sampler = SamplerKind::Jittered;
    ImageF jittered = test::render(scene, options);
    double sum = 0;
    for (size_t i = 0; i < random.rgba.size(); ++i)
      sum += std::abs(random.rgba[i] - jittered.rgba[i]);
    CHECK(sum / double(random.rgba.size()) < 0.01);
  }

  TEST_CASE("every official scene renders to a finite, non-blank image" * test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    for (const auto& entry :
         std::filesystem::recursive_directory_iterator(shared / "scene-format" / "official")) {
      if (entry.path().extension() != ".json") continue;
      CAPTURE(entry.path());
      Scene scene = loadJsonScene(entry.path());
      RenderOptions options;
      options.width = 60;
      options.height = 40;
      options.samplesPerPixel = 2;
      ImageF image = test::render(scene, options);
      CHECK(allFinite(image));
      float first = image.rgba[0];
      bool varied = false;
      for (size_t i = 0; i < image.rgba.size(); i += 4) varied |= image.rgba[i] != first;
      CHECK(varied);
    }
  }
}

namespace {

struct StatsOfTwo {
  RenderStats first;
  RenderStats second;
};

// Renders `scene` twice, `first` and then `second` applied to `options`,
// with rays counted, and checks that the two images are equal to the bit
// and traced as many rays: for options that must not change the image.
StatsOfTwo checkSameRender(const Scene& scene, RenderOptions options,
                           const std::function<void(RenderOptions&)>& first,
                           const std::function<void(RenderOptions&)>& second) {
  options.countRays = true;
  StatsOfTwo stats;
  first(options);
  const ImageF firstImage = test::render(scene, options, &stats.first);
  second(options);
  const ImageF secondImage = test::render(scene, options, &stats.second);
  CHECK(bitwiseEqual(firstImage, secondImage));
  CHECK(allFinite(secondImage));
  CHECK(stats.first.raysTraced == stats.second.raysTraced);
  return stats;
}

}  // namespace

// The scene arrays read as texel buffers or as storage buffers of the same
// bytes (SceneArrays): the same kernel code around either, so the same image.
TEST_SUITE("render") {
  // Renders `scene` both ways and checks the images are bit for bit equal.
  void checkSameImageFromEitherArrays(const Scene& scene) {
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.samplesPerPixel = 3;
    const StatsOfTwo stats = checkSameRender(
        scene, options, [](RenderOptions& o) { o.sceneArrays = SceneArrays::TexelBuffers; },
        [](RenderOptions& o) { o.sceneArrays = SceneArrays::StorageBuffers; });
    // Texel buffers as asked, unless the device misreads them (lavapipe at
    // other vector widths than 256 bits), where both renders read storage.
    CHECK(stats.first.features.storageBuffers == texelBuffersMisread(test::gpu()));
    CHECK(stats.second.features.storageBuffers);
  }

  TEST_CASE("storage-buffer scene arrays give the texel buffers' image") {
    // Spheres, cylinders, meshes, loose triangles, mirrors and glass.
    checkSameImageFromEitherArrays(test::projectScene("default.json"));
    // Area lights (emitters) and point lights.
    checkSameImageFromEitherArrays(test::projectScene("study-arealight.json"));
    // Textures, on the default scene's materials.
    Scene textured = test::projectScene("default.json");
    textured.textures.push_back(
        {"checker", {2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 128, 128, 128, 255}}});
    for (Material& material : textured.materials) material.diffuseTexture = 0;
    checkSameImageFromEitherArrays(textured);
    test::checkNoValidationMessages();
  }

  TEST_CASE("storage-buffer scene arrays: per-vertex normals and UVs (the common scene)" *
            test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    checkSameImageFromEitherArrays(
        loadJsonScene(shared / "bench" / "common-scene" / "common_pinhole.json"));
    test::checkNoValidationMessages();
  }
}

// Rays that start together walked two by two (Walks::Paired, traversePair):
// a shading point's shadow rays, binary mode's primary rays. Each ray finds
// the same hits as a walk of its own and the sums are made in the same
// order, so the image is the same to the bit, and so is the count of rays,
// which adaptive sampling weighs tiles by.
TEST_SUITE("render") {
  struct PairsExpected {
    bool shadow = true;
    bool primary = false;
  };

  void checkPairedWalksMatch(const Scene& scene, const RenderOptions& options,
                             PairsExpected expected = {}) {
    const StatsOfTwo stats = checkSameRender(
        scene, options, [](RenderOptions& o) { o.walks = Walks::Single; },
        [](RenderOptions& o) { o.walks = Walks::Paired; });
    CHECK_FALSE(stats.first.features.shadowPairs);
    CHECK_FALSE(stats.first.features.primaryPairs);
    CHECK(stats.second.features.shadowPairs == expected.shadow);
    CHECK(stats.second.features.primaryPairs == expected.primary);
  }

  // 3 samples: the last of a pixel's pairs of primary rays has one ray.
  RenderOptions pairedWalksRender() {
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.samplesPerPixel = 3;
    return options;
  }

  TEST_CASE("paired shadow walks give the single walks' image and ray count") {
    // Two point lights; spheres, cylinders, a mesh, mirrors, and glass that
    // shadow rays cross (closest-hit walks from crossing to crossing).
    const Scene defaultScene = test::projectScene("default.json");
    checkPairedWalksMatch(defaultScene, pairedWalksRender());
    // A point light and an area light.
    Scene areaLit = test::projectScene("study-arealight.json");
    checkPairedWalksMatch(areaLit, pairedWalksRender());
    // Three light samples: the last pair walks one ray.
    REQUIRE(areaLit.areaLights.size() == 1);
    areaLit.areaLights[0].samples = 2;
    checkPairedWalksMatch(areaLit, pairedWalksRender());
    // The path tracer, whose shadow rays stop at any hit (glass blocks them:
    // sampled bounces carry the light through it).
    Scene cornell = test::projectScene("cornell-pathtraced.json");
    REQUIRE(cornell.areaLights.size() == 1);
    cornell.areaLights[0].samples = 2;
    checkPairedWalksMatch(cornell, pairedWalksRender());
    // Adaptive sampling, whose rounds read the rays each tile traced.
    RenderOptions adaptive = pairedWalksRender();
    adaptive.adaptive = true;
    adaptive.keepErrorImage = true;
    checkPairedWalksMatch(defaultScene, adaptive);
    // One light: nothing to pair, the single walk is built.
    Scene oneLight = defaultScene;
    oneLight.pointLights.resize(1);
    checkPairedWalksMatch(oneLight, pairedWalksRender(), {.shadow = false});
    test::checkNoValidationMessages();
  }

  TEST_CASE("paired primary walks in binary mode give the single walks' image and ray count") {
    Scene binary = test::projectScene("default.json");
    binary.settings.mode = RenderMode::Binary;
    const PairsExpected primaryOnly{.shadow = false, .primary = true};
    checkPairedWalksMatch(binary, pairedWalksRender(), primaryOnly);
    RenderOptions adaptive = pairedWalksRender();
    adaptive.adaptive = true;
    adaptive.keepErrorImage = true;
    checkPairedWalksMatch(binary, adaptive, primaryOnly);
    test::checkNoValidationMessages();
  }
}

// On CPU devices subgroups take runs of pixels from a queue (WorkQueue,
// trace.comp) instead of each workgroup rendering its own block: every
// pixel is still computed by itself, so the image is the same to the bit,
// and so is the count of rays.
TEST_SUITE("render") {
  void checkWorkQueueMatches(const Scene& scene, const RenderOptions& options) {
    const StatsOfTwo stats = checkSameRender(
        scene, options, [](RenderOptions& o) { o.workQueue = WorkQueue::Off; },
        [](RenderOptions& o) { o.workQueue = WorkQueue::OnCpu; });
    CHECK_FALSE(stats.first.features.workQueue);
    CHECK(stats.second.features.workQueue == workQueueAvailable(test::gpu()));
  }

  TEST_CASE("the work queue gives the grid's image and ray count") {
    // Where the queue is built: lavapipe from Mesa 25 on, whose version only
    // its driver text gives (the suite runs on Mesa 25's lavapipe).
    if (test::gpu().description().driver.find("llvmpipe") != std::string::npos) {
      const std::optional<uint32_t> mesa = test::gpu().lavapipeMesaMajor();
      REQUIRE(mesa.has_value());
      CHECK(*mesa >= 22);
      CHECK(workQueueAvailable(test::gpu()) == (*mesa >= 25));
    }
    const Scene glass = test::projectScene("default.json");
    // A size that is no multiple of the 8x8 workgroups: partial blocks.
    RenderOptions options;
    options.width = 61;
    options.height = 45;
    options.samplesPerPixel = 3;
    checkWorkQueueMatches(glass, options);
    // Bands of eight rows, one dispatch each: the queue starts empty in each.
    options.secondsPerDispatch = options.secondsPerPass = 1e-9;
    checkWorkQueueMatches(glass, options);
    // A region of the image, and adaptive rounds, whose tiles count rays.
    RenderOptions region;
    region.width = 64;
    region.height = 48;
    region.region = PixelRegion{9, 5, 30, 27};
    region.samplesPerPixel = 2;
    checkWorkQueueMatches(glass, region);
    RenderOptions adaptive;
    adaptive.width = 64;
    adaptive.height = 48;
    adaptive.samplesPerPixel = 3;
    adaptive.adaptive = true;
    adaptive.keepErrorImage = true;
    checkWorkQueueMatches(glass, adaptive);
    // Binary mode's paired primary walks, and the path tracer.
    Scene binary = glass;
    binary.settings.mode = RenderMode::Binary;
    checkWorkQueueMatches(binary, options);
    checkWorkQueueMatches(test::projectScene("cornell-pathtraced.json"), options);
    test::checkNoValidationMessages();
  }
}

// A Blender export (formats/json/BlenderExport), end to end: Blender's
// camera, cube, light power and world colour.
TEST_SUITE("render") {
  TEST_CASE("the default cube, lit by the default light, renders where Blender draws it") {
    // Blender's startup scene as an exporter writes it, on a 64 x 36 image.
    const rt::Scene scene = rt::parseJsonScene(R"({
      "cameras": [{"location": [7.3589, -6.9258, 4.9583],
                   "gaze_vector": [-0.6516, 0.6142, -0.4453],
                   "up_vector": [-0.3240, 0.3054, 0.8954], "focal_length": 50,
                   "sensor_width": 36, "sensor_height": 24, "film_resolution": [64, 36]}],
      "point_lights": [{"location": [4.0762, 1.0055, 5.9039], "radiant_intensity": 1000}],
      "cubes": [{"translation": [0, 0, 0], "rotation": [0, 0, 0], "scale": 1}]})",
                                               "startup.json");
    rt::RenderOptions options;
    options.samplesPerPixel = 4;
    const rt::ImageF image = rt::test::render(scene, options);
    const float center = image.pixel(32, 18)[0];
    const float corner = image.pixel(1, 1)[0];
    // The cube fills the middle of the frame and is lit; the corner is the world's grey.
    CHECK(center > 0.1f);
    CHECK(corner == doctest::Approx(0.050876f).epsilon(0.01));
    // The face towards the light is brighter than the one away from it.
    CHECK(image.pixel(38, 18)[0] != doctest::Approx(image.pixel(26, 18)[0]).epsilon(0.05));
  }
}
