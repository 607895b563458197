// rt-bench-bvh: prints a table of the acceleration structure on generated
// meshes (1k to 5M triangles) and the Stanford bunny: BVH build time and
// rate, GPU bytes per triangle, primary and diffuse-bounce ray rates, and
// the BVH on/off render-time ratio on a coursework scene. Not a test: it
// asserts nothing and is run on demand (bench/run-bvh.sh).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "PlainBvhKernel.hpp"
#include "bvh/Bvh.hpp"
#include "encode/FlatScene.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/BatchIntersector.hpp"
#include "render/Renderer.hpp"
#include "scene/ProceduralMesh.hpp"
#include "util/Clock.hpp"

namespace {

using rt::processCpuSeconds;
using rt::secondsSince;
using Clock = rt::SteadyClock;

// Primary rays: a square image of this width, this many samples a pixel.
constexpr uint32_t kPrimaryWidth = 512;
constexpr uint32_t kPrimarySamples = 8;

// A closed bumpy sphere of about `triangles` triangles (radius about 1),
// flat shaded (no vertex records: the table counts the BVH and the triangles).
rt::TriangleMesh bumpySphere(uint32_t triangles) {
  rt::BumpySphereShape shape;
  shape.rings = std::max(2u, static_cast<uint32_t>(std::sqrt(triangles / 4.0)));
  shape.segments = 2 * shape.rings;
  shape.bump = 0.05f;
  shape.phiWaves = 9.0f;
  shape.thetaWaves = 7.0f;
  rt::TriangleMesh mesh = rt::bumpySphere(shape);
  mesh.normals.clear();
  return mesh;
}

// The mesh alone, seen whole by a pinhole camera, binary mode: primary rays only.
rt::Scene meshScene(rt::TriangleMesh mesh) {
  rt::Scene scene;
  rt::Aabb bounds;
  for (const glm::vec3& p : mesh.positions) bounds.grow(p);
  float radius = 0.5f * glm::length(bounds.max - bounds.min);
  scene.settings.mode = rt::RenderMode::Binary;
  scene.camera.fovYDegrees = 40.0f;
  scene.camera.forward = {0.0f, 0.0f, -1.0f};
  scene.camera.position = bounds.center() + glm::vec3(0.0f, 0.0f, 2.6f * radius);
  scene.materials.push_back({});
  scene.meshes.push_back(std::move(mesh));
  scene.shapes.push_back({rt::MeshInstance{0, rt::WorldTransform(1.0)}, 0, ""});
  return scene;
}

// Diffuse bounces: cosine-distributed rays leaving random surface points.
std::vector<rt::gpu::GpuRay> diffuseRays(const rt::TriangleMesh& mesh, size_t count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<size_t> pick(0, mesh.faces.size() - 1);
  std::vector<rt::gpu::GpuRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    glm::uvec3 f = mesh.faces[pick(rng)];
    glm::vec3 a = mesh.positions[f.x], b = mesh.positions[f.y], c = mesh.positions[f.z];
    glm::vec3 n = glm::cross(b - a, c - a);
    if (!(glm::length(n) > 0.0f)) continue;
    n = glm::normalize(n);
    float u = unit(rng), v = unit(rng);
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    glm::vec3 p = a + u * (b - a) + v * (c - a);
    glm::vec3 t = glm::normalize(
        glm::cross(std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), n));
    float r = std::sqrt(unit(rng)), phi = 2.0f * glm::pi<float>() * unit(rng);
    glm::vec3 d = r * std::cos(phi) * t + r * std::sin(phi) * glm::cross(n, t) +
                  std::sqrt(std::max(0.0f, 1.0f - r * r)) * n;
    rays.push_back({p + 1e-4f * n, 0.0f, d, 1e30f});
  }
  return rays;
}

struct Row {
  std::string label;
  size_t triangles = 0;
  double buildSeconds = 0;
  double bytesPerTriangle = 0;
  double primaryMrays = 0;
  double diffuseMqueries = 0;
  double primaryCpuMrays = 0;  // per CPU-second of the whole process (all driver threads)
  double diffuseCpuMqueries = 0;
};

Row measure(const std::string& label, rt::TriangleMesh mesh, rt::Renderer& renderer,
            rt::VulkanContext& context, const rt::ShaderCompiler& compiler,
            rt::AccelKind accel = rt::AccelKind::Bvh) {
  Row row{label, mesh.faces.size()};
  std::vector<rt::Aabb> boxes = rt::triangleBounds(mesh.positions, mesh.faces);
  auto start = Clock::now();
  rt::BvhBuildOptions build;
  build.maxDepth = RT_BVH_MAX_DEPTH;
  rt::Bvh bvh = rt::buildBvh(boxes, build);
  row.buildSeconds = secondsSince(start);

  std::vector<rt::gpu::GpuRay> diffuse = diffuseRays(mesh, 1u << 20);
  rt::Scene scene = meshScene(std::move(mesh));
  rt::FlatScene flat = rt::flattenScene(scene);
  size_t bytes = flat.items.size() * sizeof(rt::gpu::GpuItem) +
                 flat.bvhNodes.size() * sizeof(rt::gpu::GpuBvhNode) +
                 flat.primitives.size() * sizeof(rt::gpu::GpuPrimitive) +
                 flat.vertices.size() * sizeof(rt::gpu::GpuVertex);
  row.bytesPerTriangle = double(bytes) / double(row.triangles);

  rt::RenderOptions options;
  options.width = kPrimaryWidth;
  options.height = kPrimaryWidth;
  options.samplesPerPixel = kPrimarySamples;
  options.countRays = true;
  options.accel = accel;
  // Best of three renders: on a shared machine single runs vary by 30%.
  for (int repetition = 0; repetition < 3; ++repetition) {
    rt::RenderStats stats;
    renderer.render(scene, options, {}, &stats);
    double rays = double(stats.raysTraced);
    row.primaryMrays = std::max(row.primaryMrays, rays / stats.renderSeconds * 1e-6);
    row.primaryCpuMrays = std::max(row.primaryCpuMrays, rays / stats.renderCpuSeconds * 1e-6);
  }

  rt::FlattenOptions flatten;
  flatten.accel = accel;
  rt::BatchIntersector intersector(context, compiler, scene, flatten);
  intersector.intersect(std::vector<rt::gpu::GpuRay>(diffuse.begin(), diffuse.begin() + 4096));
  start = Clock::now();
  double cpuStart = processCpuSeconds();
  intersector.intersect(diffuse);
  // The batch kernel answers a closest-hit and an any-hit query per ray.
  row.diffuseMqueries = 2.0 * double(diffuse.size()) / secondsSince(start) * 1e-6;
  row.diffuseCpuMqueries = 2.0 * double(diffuse.size()) / (processCpuSeconds() - cpuStart) * 1e-6;
  std::fprintf(stderr, "%s: done\n", label.c_str());
  return row;
}

// Render time without a BVH over render time with one, on a scene file.
double onOffRatio(const std::string& path, rt::Renderer& renderer) {
  rt::Scene scene = rt::loadJsonScene(path);
  rt::RenderOptions options;
  options.width = 200;
  options.height = 200;
  options.samplesPerPixel = 4;
  double seconds[2] = {0, 0};
  for (rt::AccelKind accel : {rt::AccelKind::Bvh, rt::AccelKind::None}) {
    options.accel = accel;
    rt::RenderStats stats;
    renderer.render(scene, options, {}, &stats);  // first run compiles the kernel
    renderer.render(scene, options, {}, &stats);
    seconds[accel == rt::AccelKind::None] = stats.renderSeconds;
  }
  return seconds[1] / seconds[0];
}

// The plain reference kernel on the bunny, with the renderer's camera.
void printPlainReference(rt::VulkanContext& context, const rt::TriangleMesh& bunny) {
  rt::Scene scene = meshScene(bunny);
  bench::PlainCamera camera{glm::vec3(scene.camera.position),
                            std::tan(glm::radians(scene.camera.fovYDegrees) * 0.5f)};
  std::printf(
      "\nplain reference kernel (bench/PlainBvhKernel.hpp) on the bunny, same camera, image size, "
      "samples and BVH build, best of 3\n\n");
  std::printf("| %-52s | %15s | %14s | %12s |\n|---|---|---|---|\n", "nodes, triangles in",
              "primary Mrays/s", "primary /CPU-s", "rays hitting");
  struct Variant {
    const char* label;
    bench::PlainLayout layout;
  };
  const Variant variants[] = {
      {"binary, texel buffers", {}},
      {"binary, storage buffers", {.storageBuffers = true}},
      {"4-wide, texel buffers", {.wide = true}},
      {"4-wide, storage buffers", {.storageBuffers = true, .wide = true}},
      {"4-wide half floats, texel buffers", {.halfWide = true}},
      {"binary, device addresses", {.deviceAddress = true}},
      {"binary, register stack", {.registerStack = true}},
      {"binary half floats, register stack", {.halfBinary = true, .registerStack = true}},
      {"binary half floats, storage buffers, register stack",
       {.storageBuffers = true, .halfBinary = true, .registerStack = true}},
      {"4-wide half floats, register stack", {.halfWide = true, .registerStack = true}}};
  for (const Variant& variant : variants) {
    // Device addresses are enabled with ray queries only (VulkanContext).
    if (variant.layout.deviceAddress && !context.rayQueriesEnabled()) continue;
    bench::PlainResult r = bench::measurePlainBvh(context, bunny, camera, variant.layout,
                                                  kPrimaryWidth, kPrimarySamples);
    std::printf("| %-52s | %15.2f | %14.2f | %11.1f%% |\n", variant.label, r.mraysPerSecond,
                r.mraysPerCpuSecond, 100.0 * r.hitFraction);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<uint32_t> sizes{1000, 10000, 100000, 1000000, 5000000};
  std::string bunny;
  std::vector<std::string> onOffScenes;
  bool plain = false;
  CLI::App app{"Acceleration structure table: generated meshes and the bunny", "rt-bench-bvh"};
  app.add_option("--sizes", sizes, "Triangle counts of the generated meshes");
  app.add_option("--bunny", bunny, "The Stanford bunny PLY (bun_zipper.ply)");
  app.add_option("--on-off", onOffScenes, "Scene files for the BVH on/off render-time ratio");
  app.add_flag("--plain", plain, "Also time the plain reference kernel on the bunny");
  CLI11_PARSE(app, argc, argv);
  try {
    rt::ContextOptions contextOptions;
    contextOptions.rayQueries = rt::RayQueries::IfSupported;
    rt::VulkanContext context(contextOptions);
    rt::ShaderCompiler compiler(rt::ShaderCompiler::defaultShaderDir(),
                                rt::ShaderCompiler::defaultCacheDir());
    rt::Renderer renderer(context, compiler);
    std::vector<Row> rows;
    for (uint32_t size : sizes) {
      rows.push_back(measure(fmt::format("bumpy sphere {}", size), bumpySphere(size), renderer,
                             context, compiler));
    }
    rt::TriangleMesh bunnyMesh;
    if (!bunny.empty()) {
      bunnyMesh = rt::loadPly(bunny);
      rows.push_back(measure("Stanford bunny", bunnyMesh, renderer, context, compiler));
      // The same through the driver's acceleration structures (ray queries).
      if (context.rayQueriesEnabled()) {
        rows.push_back(measure("bunny, --accel hardware", bunnyMesh, renderer, context, compiler,
                               rt::AccelKind::Hardware));
      }
    }
    std::printf(
        "device: %s; %u hardware threads; primary: %ux%u, %u spp, binary mode, best of 3; "
        "diffuse: 2^20 cosine rays from the surface, closest + any hit each\n\n",
        context.description().summary().c_str(), std::thread::hardware_concurrency(), kPrimaryWidth,
        kPrimaryWidth, kPrimarySamples);
    std::printf("| %-24s | %9s | %8s | %10s | %9s | %15s | %16s | %13s | %14s |\n", "mesh",
                "triangles", "build s", "Mtris/s", "bytes/tri", "primary Mrays/s",
                "diffuse Mquery/s", "primary /CPU-s", "diffuse /CPU-s");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
      std::printf("| %-24s | %9zu | %8.3f | %10.2f | %9.1f | %15.2f | %16.2f | %13.2f | %14.2f |\n",
                  r.label.c_str(), r.triangles, r.buildSeconds,
                  double(r.triangles) / r.buildSeconds * 1e-6, r.bytesPerTriangle, r.primaryMrays,
                  r.diffuseMqueries, r.primaryCpuMrays, r.diffuseCpuMqueries);
    }
    if (!onOffScenes.empty()) std::printf("\n| scene | render time, BVH off / on |\n|---|---|\n");
    for (const std::string& path : onOffScenes) {
      std::printf("| %s | %.2f |\n", path.c_str(), onOffRatio(path, renderer));
    }
    if (plain && !bunny.empty()) printPlainReference(context, bunnyMesh);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
