// Extreme inputs: every pixel stays finite without the renderer's NaN/Inf
// safety net (unguardedCompiler()), and images match what physics says.
#include <doctest/doctest.h>

#include "render/BatchIntersector.hpp"
#include "robustness/RobustnessSupport.hpp"

using namespace rt;
using namespace rt::test;

namespace {

// Camera on +z looking at the origin, one point light up and to the right
// (family B: no falloff).
Scene stage(uint32_t width = 40, uint32_t height = 30) {
  Scene scene = test::frontStage(width, height, {3, 4, 6}, 0.9f);
  scene.settings.maxBounces = 8;
  return scene;
}

Material glass(float ior, float transmission = 1.0f) {
  Material m = matte(glm::vec3(0.0f));
  m.kd = 0.0f;
  m.transmission = transmission;
  m.ior = ior;
  return m;
}

Material mirror(float reflectivity) {
  Material m = matte(glm::vec3(0.0f));
  m.kd = 0.0f;
  m.reflectivity = reflectivity;
  return m;
}

// A matte sphere behind the origin on a matte floor: what glass is seen against.
void addBackdrop(Scene& scene) {
  addShape(scene, Sphere{{0.4f, 0.1f, -3}, 1.2f}, matte({0.9f, 0.6f, 0.1f}));
  addShape(scene, Quad{{-6, -1.5f, 4}, {6, -1.5f, 4}, {6, -1.5f, -8}, {-6, -1.5f, -8}},
           matte({0.5f, 0.7f, 0.5f}));
}

double meanDifference(const ImageF& a, const ImageF& b) {
  double sum = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 != 3) sum += std::abs(double(a.rgba[i]) - double(b.rgba[i]));
  }
  return sum / double(a.rgba.size() / 4 * 3);
}

glm::dvec3 meanColor(const ImageF& image) {
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    sum += glm::dvec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
  }
  return sum / double(image.rgba.size() / 4);
}

bool finiteUnit(glm::vec3 n) {
  return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) &&
         std::abs(glm::length(n) - 1.0f) < 1e-4f;
}

}  // namespace

TEST_SUITE("robustness-edge") {
  TEST_CASE("tiny, far, huge and grazed spheres and degenerate triangles: no NaN or Inf") {
    Scene scene = stage();
    addBackdrop(scene);
    addShape(scene, Sphere{{0.5f, 0.5f, -1e4f}, 1e-3f}, matte(glm::vec3(1)));  // subpixel, far
    addShape(scene, Sphere{{0, 0, -1e7f}, 1e4f}, matte(glm::vec3(1)));         // huge, farther
    addShape(scene, Sphere{{-0.2f, 0.3f, 4.99f}, 1e-6f}, mirror(1));           // tiny, at the eye
    Material glassy = glass(1.5f);
    glassy.reflectivity = 0.2f;
    addShape(scene, Sphere{{-1.2f, -0.3f, 0}, 0.5f}, glassy);
    Scene plain = scene;
    // Zero area (a point), collinear corners, and a needle: no surface to hit.
    for (Triangle t : {Triangle{{0.1f, 0.1f, 1}, {0.1f, 0.1f, 1}, {0.1f, 0.1f, 1}},
                       Triangle{{-1, -1, 1}, {0, 0, 1}, {1, 1, 1}},
                       Triangle{{-1, 0.5f, 0.5f}, {1, 0.5f, 0.5f}, {3, 0.5f, 0.5f}},
                       Triangle{{-1, -0.2f, 2}, {1, -0.2f, 2}, {1, -0.2f, 2}}}) {
      addShape(scene, t, matte(glm::vec3(1)));
    }
    ImageF withDegenerate = render(scene, 2, unguardedCompiler());
    CHECK(nonFiniteValues(withDegenerate) == 0);
    CHECK(bitwiseEqual(withDegenerate, render(plain, 2, unguardedCompiler())));

    // Grazing: the eye a hair above a vast floor, looking along it.
    Scene grazing = stage();
    grazing.camera.position = {0, 1e-4f, 5};
    grazing.camera.forward = glm::normalize(glm::vec3(0, -1e-5f, -1));
    addShape(grazing, Quad{{-1e5f, 0, 1e5f}, {1e5f, 0, 1e5f}, {1e5f, 0, -1e5f}, {-1e5f, 0, -1e5f}},
             mirror(0.5f));
    addShape(grazing, Sphere{{0, 1, -20}, 1}, glass(1.33f));
    CHECK(nonFiniteValues(render(grazing, 2, unguardedCompiler())) == 0);
  }

  TEST_CASE("rays tangent to spheres and cylinders, and in the plane of triangles") {
    Scene scene;
    scene.materials.push_back({});
    scene.shapes.push_back({Sphere{{1, 0, 0}, 1}, 0, ""});
    scene.shapes.push_back({Cylinder{{0, 5, 0}, {0, 1, 0}, 1, 1}, 0, ""});
    scene.shapes.push_back({Triangle{{-1, -5, -1}, {1, -5, -1}, {0, -5, 1}}, 0, ""});
    std::vector<gpu::GpuRay> rays = {
        {{0, 0, 5}, 0, {0, 0, -1}, 3e38f},   // touches the sphere at the origin
        {{2, 0, 5}, 0, {0, 0, -1}, 3e38f},   // touches it at (2, 0, 0)
        {{1, 1, 5}, 0, {0, 0, -1}, 3e38f},   // over its top
        {{1, 5, 5}, 0, {0, 0, -1}, 3e38f},   // touches the cylinder side
        {{0, 6, 5}, 0, {0, 0, -1}, 3e38f},   // in the plane of the top cap
        {{0, 4, 5}, 0, {0, 0, -1}, 3e38f},   // in the plane of the bottom cap
        {{-3, -5, 0}, 0, {1, 0, 0}, 3e38f},  // in the triangle's plane, through it
        {{0, -5, -3}, 0, {0, 0, 1}, 3e38f},  // along its plane, through a corner
    };
    BatchIntersector intersector(rt::test::gpu(), shaderCompiler(), scene);
    std::vector<gpu::GpuHit> hits = intersector.intersect(rays);
    for (size_t i = 0; i < hits.size(); ++i) {
      CAPTURE(i);
      CHECK(std::isfinite(hits[i].t));
      if (hits[i].t >= 0) CHECK(finiteUnit(hits[i].normal));
    }
    // A ray in a triangle's plane meets no area; the caps are met edge on.
    CHECK(hits[6].t < 0);
    CHECK(hits[7].t < 0);
    checkNoValidationMessages();
  }

  TEST_CASE("glass with eta 1 is invisible, eta 1.0001 nearly so, eta 4 stays finite") {
    Scene scene = stage();
    addBackdrop(scene);
    Scene withGlass = scene;
    addShape(withGlass, Sphere{{-0.3f, 0, 1}, 1}, glass(1.0f));
    ImageF plain = render(scene, 2, unguardedCompiler());
    ImageF clear = render(withGlass, 2, unguardedCompiler());
    CHECK(nonFiniteValues(clear) == 0);
    // Rays go straight through from origins offset by ~1e-6: only a sample
    // within that of an edge behind may change.
    CHECK(pixelsDiffering(clear, plain, 1e-3f) <= 1);
    withGlass.materials.back().ior = 1.0001f;
    ImageF nearlyClear = render(withGlass, 2, unguardedCompiler());
    CHECK(nonFiniteValues(nearlyClear) == 0);
    CHECK(meanDifference(nearlyClear, plain) < 2e-3);
    withGlass.materials.back().ior = 4.0f;
    CHECK(nonFiniteValues(render(withGlass, 2, unguardedCompiler())) == 0);
  }

  TEST_CASE("white furnace: lossless glass in a uniform background shows the background") {
    // Fresnel reflectance and transmittance sum to one at every interface,
    // total internal reflection included, so with no lights and black
    // matte terms every path ends in the background at full weight (minus
    // the ray tree's 1e-4 floor, with the bailout off, and the depth limit).
    for (float ior : {1.0001f, 1.5f, 4.0f}) {
      CAPTURE(ior);
      Scene scene = stage(16, 12);
      scene.pointLights.clear();
      scene.backgroundColor = glm::vec3(0.5f);
      scene.settings.maxBounces = 64;
      scene.settings.branchBailout = 0.0f;
      addShape(scene, Sphere{{-1, 0, 0}, 1}, glass(ior));
      addShape(scene, Sphere{{-1, 0, 0}, 0.5f}, glass(ior * 1.3f));  // nested glass
      TriangleMesh cube = placed(icosphere(0), 1.0, {1.4, 0, 0});    // a glass polyhedron
      addMesh(scene, cube, glass(ior));
      ImageF image = render(scene, 4, unguardedCompiler());
      REQUIRE(nonFiniteValues(image) == 0);
      glm::dvec3 mean = meanColor(image);
      // At ior 4 (total internal reflection in most directions) the depth
      // limit and the cutoff lose 2.1% (mean 0.4893, measured).
      CHECK(mean.x == doctest::Approx(0.5).epsilon(0.03).scale(0));
      CHECK(mean.y == doctest::Approx(0.5).epsilon(0.03).scale(0));
    }
  }

  TEST_CASE("specular exponents 0 and 1e6: pow(0, 0) is 1, a needle highlight, no NaN") {
    // Exponent 0 makes the highlight 1 wherever the light is above the
    // surface: at the centre pixel L = kd Cd I + ks Cs I, as with any
    // exponent there.
    Scene scene = stage(41, 41);
    scene.pointLights = {{{0, 0, 50}, glm::vec3(0.8f), glm::vec3(0.8f)}};
    Material shiny = matte({0.5f, 0.25f, 1.0f});
    shiny.kd = 0.6f;
    shiny.ks = 0.3f;
    shiny.specularExponent = 0.0f;
    addShape(scene, Sphere{{0, 0, 0}, 1}, shiny);
    // A triangle whose shading normal leans away from the viewer: n.h < 0
    // while n.l > 0, so the highlight base is clamped to exactly 0 and the
    // highlight is pow(0, 0), here 1.
    TriangleMesh leaning;
    leaning.positions = {{1.2f, -1.4f, 0.5f}, {1.9f, -1.4f, 0.5f}, {1.2f, -0.7f, 0.5f}};
    leaning.faces = {{0, 1, 2}};
    glm::vec3 lean = glm::normalize(glm::vec3(1, 0, 0.05f));
    leaning.normals = {lean, lean, lean};
    addMesh(scene, leaning, shiny);
    ImageF flat = render(scene, 1, unguardedCompiler());
    CHECK(nonFiniteValues(flat) == 0);
    const float* centre = flat.pixel(20, 20);
    glm::vec3 expected = 0.8f * (0.6f * glm::vec3(0.5f, 0.25f, 1.0f) + 0.3f * glm::vec3(1.0f));
    CHECK(std::abs(centre[0] - expected.x) < 2e-3f);
    CHECK(std::abs(centre[2] - expected.z) < 2e-3f);
    // (1.4, -1.2, 0.5) on the triangle, 4.5 from the eye: 12.5 pixels a unit.
    const uint32_t onTriangleX = 20 + uint32_t(1.4 * 12.5), onTriangleY = 20 + uint32_t(1.2 * 12.5);
    Scene dullScene = scene;
    dullScene.materials[1].ks = 0.0f;
    ImageF dullTriangle = render(dullScene, 1, unguardedCompiler());
    float highlight =
        flat.pixel(onTriangleX, onTriangleY)[1] - dullTriangle.pixel(onTriangleX, onTriangleY)[1];
    CHECK(highlight == doctest::Approx(0.3f * 0.8f).epsilon(1e-4).scale(0));

    scene.materials[0].specularExponent = 1e6f;
    scene.materials[1].specularExponent = 1e6f;
    ImageF needle = render(scene, 1, unguardedCompiler());
    CHECK(nonFiniteValues(needle) == 0);
    scene.materials[0].ks = 0.0f;
    scene.materials[1].ks = 0.0f;
    ImageF dull = render(scene, 1, unguardedCompiler());
    // A lobe of width ~1e-3 rad covers at most a pixel or two.
    CHECK(pixelsDiffering(needle, dull, 1e-3f) <= 2);
  }

  TEST_CASE("nbounces 0 and 64, facing mirrors, zero aperture") {
    Scene scene = stage(32, 24);
    addShape(scene, Sphere{{0, 0, 0}, 1}, mirror(1));
    scene.settings.maxBounces = 0;
    ImageF direct = render(scene, 1, unguardedCompiler());
    const float* centre = direct.pixel(16, 12);
    CHECK(centre[0] == 0.0f);  // a perfect mirror has no direct light of its own
    CHECK(centre[2] == 0.0f);

    // Two parallel mirrors with the camera between: 64 bounces, each losing
    // 10%, never more light than the background they finally show.
    Scene corridor = stage(32, 24);
    corridor.settings.maxBounces = 64;
    corridor.camera.forward = glm::normalize(glm::vec3(1, 0.05f, -0.1f));
    addShape(corridor, Quad{{2, -50, 50}, {2, -50, -50}, {2, 50, -50}, {2, 50, 50}}, mirror(0.9f));
    addShape(corridor, Quad{{-2, -50, -50}, {-2, -50, 50}, {-2, 50, 50}, {-2, 50, -50}},
             mirror(0.9f));
    ImageF bounced = render(corridor, 1, unguardedCompiler());
    CHECK(nonFiniteValues(bounced) == 0);
    for (size_t i = 0; i < bounced.rgba.size(); i += 4) {
      CHECK(bounced.rgba[i + 2] <= corridor.backgroundColor.z * (1 + 1e-5f));
    }

    Scene lens = stage(32, 24);
    addBackdrop(lens);
    lens.camera.type = CameraType::ThinLens;
    lens.camera.focusDistance = 5;
    lens.camera.apertureRadius = 0.0f;
    ImageF pinhole = render(lens, 1, unguardedCompiler());
    CHECK(nonFiniteValues(pinhole) == 0);
    lens.camera.apertureRadius = 1e-30f;
    ImageF tiny = render(lens, 1, unguardedCompiler());
    CHECK(nonFiniteValues(tiny) == 0);
    CHECK(pixelsDiffering(tiny, pinhole, 1e-3f) <= 1);
  }
}
