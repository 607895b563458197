// The GPU acceleration structure as a whole: the BVH against brute force
// through the real traversal kernel, shared meshes (instances) against
// their flattened copies, memory per instance, and a deterministic build.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "bvh/Bvh.hpp"
#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "encode/SceneBuffers.hpp"
#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "render/BatchIntersector.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "render/Renderer.hpp"
#include "scene/ProceduralMesh.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

using namespace rt;

namespace {

// Placements of one mesh: rotated, non-uniformly scaled, mirrored.
std::vector<glm::mat4> placements() {
  glm::mat4 identity(1.0f);
  return {glm::translate(identity, {-1.2f, 0.3f, 0.0f}),
          glm::scale(glm::rotate(glm::translate(identity, {1.1f, -0.2f, 0.4f}), 0.7f,
                                 glm::vec3(1, 2, 0.5f)),
                     {0.6f, 1.1f, 0.8f}),
          glm::scale(glm::translate(identity, {0.0f, 1.3f, -0.8f}), {-0.5f, 0.5f, 0.5f})};
}

// Instances of one shared mesh, or (`flattened`) of one copy per instance.
Scene meshScene(bool flattened, uint32_t instances = 3) {
  Scene scene;
  scene.materials.push_back({});
  TriangleMesh mesh = bumpySphere({24, 32});
  std::vector<glm::mat4> where = placements();
  for (uint32_t i = 0; i < instances; ++i) {
    if (flattened || scene.meshes.empty()) scene.meshes.push_back(mesh);
    glm::mat4 transform =
        glm::translate(where[i % where.size()], glm::vec3(0, 0, -0.3f * float(i / 3)));
    scene.shapes.push_back(
        {MeshInstance{uint32_t(scene.meshes.size() - 1), WorldTransform(transform)}, 0, ""});
  }
  scene.shapes.push_back({Sphere{{0.2f, -0.9f, 0.6f}, 0.5f}, 0, ""});
  scene.shapes.push_back(
      {Cylinder{{-0.4f, -0.6f, -0.9f}, glm::normalize(glm::vec3(1, 1, 0)), 0.3f, 0.5f}, 0, ""});
  scene.shapes.push_back(
      {Quad{{-2, -1.5f, -2}, {2, -1.5f, -2}, {2, -1.5f, 2}, {-2, -1.5f, 2}}, 0, ""});
  return scene;
}

std::vector<gpu::GpuRay> randomRays(size_t count, uint32_t seed) {
  return test::raysTowardsOrigin(count, seed, 2.0f);
}

struct Differences {
  size_t hits = 0;
  size_t hitMiss = 0;
  size_t distance = 0;
  size_t shape = 0;
  size_t normal = 0;
  size_t occluded = 0;
};

Differences compareHits(const std::vector<gpu::GpuHit>& a, const std::vector<gpu::GpuHit>& b) {
  Differences d;
  for (size_t i = 0; i < a.size(); ++i) {
    d.occluded += a[i].occluded != b[i].occluded;
    if ((a[i].t >= 0) != (b[i].t >= 0)) {
      ++d.hitMiss;
      continue;
    }
    if (a[i].t < 0) continue;
    ++d.hits;
    d.distance += std::abs(a[i].t - b[i].t) > 1e-4f * std::max(1.0f, a[i].t);
    d.shape += a[i].shapeIndex != b[i].shapeIndex;
    d.normal += glm::dot(a[i].normal, b[i].normal) < 0.9999f;
  }
  return d;
}

// Rays within rounding of an edge may tell the two apart: a handful in ten thousand.
void checkSame(const Differences& d, size_t rays) {
  CAPTURE(d.hits);
  CHECK(d.hits > rays / 4);
  CHECK(d.hitMiss <= rays / 2000);
  CHECK(d.distance <= rays / 2000);
  CHECK(d.shape <= rays / 2000);
  CHECK(d.normal <= rays / 2000);
  CHECK(d.occluded <= rays / 2000);
}

std::vector<gpu::GpuHit> gpuHits(const Scene& scene, const std::vector<gpu::GpuRay>& rays,
                                 AccelKind accel) {
  FlattenOptions options;
  options.accel = accel;
  BatchIntersector intersector(test::gpu(), test::shaderCompiler(), scene, options);
  return intersector.intersect(rays);
}

size_t gpuBytes(const FlatScene& flat) {
  return flat.primitives.size() * sizeof(gpu::GpuPrimitive) +
         flat.items.size() * sizeof(gpu::GpuItem) + flat.bvhNodes.size() * sizeof(gpu::GpuBvhNode) +
         flat.vertices.size() * sizeof(gpu::GpuVertex);
}

}  // namespace

TEST_SUITE("bvh-gpu") {
  TEST_CASE("BVH and brute force give the same hits (GPU traversal kernel)") {
    Scene scene = meshScene(false);
    auto rays = randomRays(6000, 11);
    checkSame(
        compareHits(gpuHits(scene, rays, AccelKind::Bvh), gpuHits(scene, rays, AccelKind::None)),
        rays.size());
    test::checkNoValidationMessages();
  }

  TEST_CASE("a mesh alone is entered at its root and hits like brute force") {
    Scene alone;
    alone.materials.push_back({});
    alone.meshes.push_back(bumpySphere({24, 32}));
    alone.shapes.push_back({MeshInstance{0, WorldTransform(1.0)}, 0, ""});
    CHECK(flattenScene(alone).info.soleInstance == 0u);
    CHECK(flattenScene(meshScene(false)).info.soleInstance == RT_NO_INSTANCE);
    auto rays = test::raysTowardsOrigin(6000, 13, 1.0f);
    checkSame(
        compareHits(gpuHits(alone, rays, AccelKind::Bvh), gpuHits(alone, rays, AccelKind::None)),
        rays.size());
    test::checkNoValidationMessages();
  }

  TEST_CASE("a shared mesh hits like its flattened copies") {
    auto rays = randomRays(20000, 12);
    checkSame(compareHits(gpuHits(meshScene(false), rays, AccelKind::Bvh),
                          gpuHits(meshScene(true), rays, AccelKind::Bvh)),
              rays.size());
    test::checkNoValidationMessages();
  }

  TEST_CASE("--accel hardware: ray queries give the BVH's hits" * test::needsRayQueries()) {
    // Shared (object-space, mirrored) instances and world-space copies,
    // spheres, a cylinder and a quad: every kind of primitive and placement.
    for (bool flattened : {false, true}) {
      CAPTURE(flattened);
      Scene scene = meshScene(flattened);
      auto rays = randomRays(20000, 13);
      checkSame(compareHits(gpuHits(scene, rays, AccelKind::Bvh),
                            gpuHits(scene, rays, AccelKind::Hardware)),
                rays.size());
    }
    test::checkNoValidationMessages();
  }

  TEST_CASE("--accel hardware renders the BVH's image" * test::needsRayQueries()) {
    Scene scene = test::projectScene("default.json");
    Renderer renderer(test::gpu(), test::shaderCompiler());
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.samplesPerPixel = 2;
    Image8 bvh = toneMap(renderer.render(scene, options), {});
    options.accel = AccelKind::Hardware;
    Image8 hardware = toneMap(renderer.render(scene, options), {});
    test::savePng(hardware, "default-accel-hardware.png");
    CHECK(test::psnr(bvh, hardware) > 50.0);
    test::checkNoValidationMessages();
  }

  TEST_CASE("only a mesh placed more than once makes the walk move rays into object space") {
    Scene shared = meshScene(false);
    CHECK(detectFeatures(shared, flattenScene(shared)).instanceTransforms);
    Scene copies = meshScene(true);  // each copy built in world space
    ShaderFeatures features = detectFeatures(copies, flattenScene(copies));
    CHECK(features.meshes);
    CHECK_FALSE(features.instanceTransforms);
    CHECK(features.looseTriangles);  // the floor quad
    Scene meshOnly;
    meshOnly.materials.push_back({});
    meshOnly.meshes.push_back(bumpySphere({4, 6}));
    meshOnly.shapes.push_back(
        {MeshInstance{0, glm::scale(WorldTransform(1.0), glm::dvec3(2.0))}, 0, ""});
    features = detectFeatures(meshOnly, flattenScene(meshOnly));
    CHECK(features.triangles);
    CHECK_FALSE(features.looseTriangles);
    CHECK_FALSE(features.instanceTransforms);
    CHECK_FALSE(features.spheres);
  }

  TEST_CASE("walks whose stack fits the registers are built without its array, and hit alike") {
    // Spheres on a jittered grid, more and more of them: the BVH grows a
    // level at a time. The deepest scene built without the array and the
    // shallowest built with it must both hit like brute force (whose own
    // tree is another shape), with rays that cross many boxes.
    auto cluster = [](uint32_t count) {
      Scene scene;
      scene.materials.push_back({});
      std::mt19937 rng(count);
      std::uniform_real_distribution<float> jitter(-0.15f, 0.15f);
      for (uint32_t i = 0; i < count; ++i) {
        glm::vec3 cell(float(i % 4), float(i / 4 % 4), float(i / 16));
        glm::vec3 centre = 0.5f * (cell - glm::vec3(1.5f)) + glm::vec3(jitter(rng), jitter(rng), 0);
        scene.shapes.push_back({Sphere{glm::dvec3(centre), 0.22f}, 0, ""});
      }
      return scene;
    };
    std::optional<uint32_t> deepestInRegisters, shallowestWithArray;
    for (uint32_t count = 2; count <= 48; ++count) {
      Scene scene = cluster(count);
      FlatScene flat = flattenScene(scene);
      bool inRegisters = detectFeatures(scene, flat).stackInRegisters;
      CAPTURE(count);
      CHECK(inRegisters == (flat.bvhDepth <= RT_BVH_STACK_REGISTERS));
      if (inRegisters) deepestInRegisters = count;
      if (!inRegisters && !shallowestWithArray) shallowestWithArray = count;
    }
    REQUIRE(deepestInRegisters);
    REQUIRE(shallowestWithArray);
    // Deeper walks vote before writing the array where that pays: lavapipe
    // from Mesa 25 on (the suite runs there), and GPUs.
    if (const std::optional<uint32_t> mesa = test::gpu().lavapipeMesaMajor()) {
      CHECK(laneVotesPay(test::gpu()) == (*mesa >= 25));
    }
    CHECK(flattenScene(cluster(*deepestInRegisters)).bvhDepth == RT_BVH_STACK_REGISTERS);
    auto rays = test::raysTowardsOrigin(6000, 14, 1.0f);
    for (uint32_t count : {*deepestInRegisters, *shallowestWithArray}) {
      CAPTURE(count);
      Scene scene = cluster(count);
      checkSame(
          compareHits(gpuHits(scene, rays, AccelKind::Bvh), gpuHits(scene, rays, AccelKind::None)),
          rays.size());
    }
    test::checkNoValidationMessages();
  }

  TEST_CASE("a shared mesh is stored once: instances cost a few hundred bytes each") {
    FlatScene few = flattenScene(meshScene(false, 2));
    FlatScene many = flattenScene(meshScene(false, 60));
    size_t triangles = meshScene(false, 1).meshes[0].faces.size();
    CHECK(many.items.size() - many.primitives.size() == triangles);
    double perInstance = double(gpuBytes(many) - gpuBytes(few)) / 58.0;
    CAPTURE(perInstance);
    CHECK(perInstance <= 256.0);
    // Flattened copies, for contrast, grow by the whole mesh.
    CHECK(gpuBytes(flattenScene(meshScene(true, 6))) >
          gpuBytes(flattenScene(meshScene(false, 6))) + 4 * triangles * sizeof(gpu::GpuItem));
  }

  TEST_CASE("instanced glTF renders like its flattened copy" * test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    Scene scene = loadGltfScene(shared /
                                "assets/gltf/khronos-sample-assets/SimpleInstancing/glTF/"
                                "SimpleInstancing.gltf");
    Scene flattened = scene;
    uint32_t instances = 0;
    for (Shape& shape : flattened.shapes) {
      if (auto* instance = std::get_if<MeshInstance>(&shape.geometry)) {
        flattened.meshes.push_back(scene.meshes[instance->mesh]);
        instance->mesh = uint32_t(flattened.meshes.size() - 1);
        ++instances;
      }
    }
    REQUIRE(instances > 1);
    Renderer renderer(test::gpu(), test::shaderCompiler());
    RenderOptions options;
    options.width = 96;
    options.height = 96;
    options.samplesPerPixel = 2;
    Image8 a = toneMap(renderer.render(scene, options), {});
    Image8 b = toneMap(renderer.render(flattened, options), {});
    test::savePng(a, "instancing-shared.png");
    CHECK(test::psnr(a, b) > 45.0);
    test::checkNoValidationMessages();
  }

  TEST_CASE("--accel none renders the image the BVH renders" * test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    Scene scene = loadJsonScene(shared / "scene-format/official/cgr-2023-2024/mirror_image.json");
    Renderer renderer(test::gpu(), test::shaderCompiler());
    RenderOptions options;
    options.width = 80;
    options.height = 60;
    options.samplesPerPixel = 2;
    Image8 bvh = toneMap(renderer.render(scene, options), {});
    options.accel = AccelKind::None;
    Image8 none = toneMap(renderer.render(scene, options), {});
    CHECK(test::psnr(bvh, none) > 45.0);
    test::checkNoValidationMessages();
  }
}

TEST_SUITE("bvh") {
  TEST_CASE("the build is the same whatever the thread count") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> position(-100.0f, 100.0f);
    std::uniform_real_distribution<float> size(0.0f, 2.0f);
    std::vector<Aabb> boxes(300000);
    for (Aabb& box : boxes) {
      glm::vec3 p(position(rng), position(rng), position(rng));
      box.grow(p);
      box.grow(p + glm::vec3(size(rng), size(rng), size(rng)));
    }
    BvhBuildOptions options;
    options.threads = 1;
    Bvh reference = buildBvh(boxes, options);
    for (uint32_t threads : {2u, 3u, 8u}) {
      CAPTURE(threads);
      options.threads = threads;
      Bvh bvh = buildBvh(boxes, options);
      REQUIRE(bvh.nodes.size() == reference.nodes.size());
      CHECK(bvh.primitiveOrder == reference.primitiveOrder);
      CHECK(bvh.depth == reference.depth);
      size_t different = 0;
      for (size_t i = 0; i < bvh.nodes.size(); ++i) {
        const BvhNode& x = bvh.nodes[i];
        const BvhNode& y = reference.nodes[i];
        different += x.firstIndex != y.firstIndex || x.count != y.count ||
                     x.bounds.min != y.bounds.min || x.bounds.max != y.bounds.max;
      }
      CHECK(different == 0);
    }
  }
}

TEST_SUITE("bvh-gpu") {
  TEST_CASE("a scene beyond the buffer limits is a one-line error, not a crash") {
    FlatScene flat = flattenScene(meshScene(false));
    SceneBufferLimits limits;
    limits.rows = flat.items.size() * RT_TEXELS_PER_ITEM - 1;
    try {
      SceneBuffers buffers(test::gpu(), flat, SceneArrays::TexelBuffers, limits);
      FAIL("no error");
    } catch (const Error& e) {
      std::string message = e.what();
      CHECK(message.find("scene too large: BVH leaf items need") == 0);
      CHECK(message.find('\n') == std::string::npos);
    }
    // Shading data is in texel buffers too: with more vertices than any
    // other buffer holds texels, the vertices are what does not fit.
    flat.vertices.resize(4 * (flat.items.size() + flat.bvhNodes.size() + flat.primitives.size()));
    limits.rows = flat.vertices.size() * RT_TEXELS_PER_VERTEX - 1;
    CHECK_THROWS_WITH_AS(SceneBuffers(test::gpu(), flat, SceneArrays::StorageBuffers, limits),
                         doctest::Contains("scene too large: vertices need"), Error);
    test::checkNoValidationMessages();
  }
}
