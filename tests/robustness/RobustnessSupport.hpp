// Helpers shared by the robustness tests: closed meshes made here, small
// renders, image comparisons.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <utility>

#include "render/Renderer.hpp"
#include "scene/Scene.hpp"
#include "support/TestSupport.hpp"

namespace rt::test {

// Icosahedron subdivided `levels` times, vertices on the unit sphere: a
// closed mesh whose triangles share vertices by index (consistent winding).
inline TriangleMesh icosphere(int levels) {
  const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh mesh;
  for (glm::vec3 p :
       {glm::vec3(-1, g, 0), glm::vec3(1, g, 0), glm::vec3(-1, -g, 0), glm::vec3(1, -g, 0),
        glm::vec3(0, -1, g), glm::vec3(0, 1, g), glm::vec3(0, -1, -g), glm::vec3(0, 1, -g),
        glm::vec3(g, 0, -1), glm::vec3(g, 0, 1), glm::vec3(-g, 0, -1), glm::vec3(-g, 0, 1)}) {
    mesh.positions.push_back(glm::normalize(p));
  }
  mesh.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, added] = midpoints.try_emplace({key.first, key.second}, 0);
      if (added) {
        it->second = uint32_t(mesh.positions.size());
        mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
      }
      return it->second;
    };
    std::vector<glm::uvec3> finer;
    for (glm::uvec3 f : mesh.faces) {
      uint32_t ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
      finer.insert(finer.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
    }
    mesh.faces = std::move(finer);
  }
  return mesh;
}

// The mesh's vertices mapped by p -> scale * p + offset (in double, rounded once).
inline TriangleMesh placed(TriangleMesh mesh, double scale, glm::dvec3 offset) {
  for (glm::vec3& p : mesh.positions) p = glm::vec3(scale * glm::dvec3(p) + offset);
  return mesh;
}

inline void addShape(Scene& scene, Geometry geometry, const Material& material) {
  scene.materials.push_back(material);
  scene.shapes.push_back({std::move(geometry), uint32_t(scene.materials.size() - 1), ""});
}

inline void addMesh(Scene& scene, TriangleMesh mesh, const Material& material) {
  scene.meshes.push_back(std::move(mesh));
  addShape(scene, MeshInstance{uint32_t(scene.meshes.size() - 1), WorldTransform(1.0)}, material);
}

inline Material matte(glm::vec3 color) {
  Material m;
  m.diffuseColor = color;
  m.kd = 1.0f;
  m.ks = 0.0f;
  return m;
}

inline ImageF render(const Scene& scene, uint32_t samples, const ShaderCompiler& compiler) {
  Renderer renderer(gpu(), compiler);
  RenderOptions options;
  options.samplesPerPixel = samples;
  options.secondsPerDispatch = 10;
  ImageF image = renderer.render(scene, options);
  checkNoValidationMessages();
  return image;
}

inline ImageF render(const Scene& scene, uint32_t samples = 1) {
  return render(scene, samples, shaderCompiler());
}

inline bool bitwiseEqual(const ImageF& a, const ImageF& b) {
  return a.rgba.size() == b.rgba.size() &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

inline size_t nonFiniteValues(const ImageF& image) {
  size_t count = 0;
  for (float v : image.rgba) count += !std::isfinite(v);
  return count;
}

// Largest per-channel difference (alpha, the sample count, left out).
inline double maxDifference(const ImageF& a, const ImageF& b) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  double worst = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    worst = std::max(worst, double(std::abs(a.rgba[i] - b.rgba[i])));
  }
  return worst;
}

// Pixels where some channel differs by more than `threshold`.
inline size_t pixelsDiffering(const ImageF& a, const ImageF& b, float threshold) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  size_t count = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    bool differs = false;
    for (size_t c = 0; c < 3; ++c) differs |= std::abs(a.rgba[i + c] - b.rgba[i + c]) > threshold;
    count += differs;
  }
  return count;
}

}  // namespace rt::test

namespace rt::test {

// A shader compiler over a copy of shaders/ in which the render kernel adds
// each sample's radiance as it is, without finiteOrZero (shaders/trace.comp):
// renders then show the NaN and Inf the safety net would hide.
inline const ShaderCompiler& unguardedCompiler() {
  static const ShaderCompiler compiler = [] {
    namespace fs = std::filesystem;
    fs::path copy = fs::path(RT_TEST_OUTPUT_DIR) / "unguarded-shaders";
    fs::remove_all(copy);
    fs::create_directories(copy);
    for (const fs::directory_entry& entry : fs::directory_iterator(RT_SOURCE_SHADER_DIR)) {
      fs::copy_file(entry.path(), copy / entry.path().filename());
    }
    std::ifstream in(copy / "trace.comp");
    std::string source((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string guarded = "finiteOrZero(radiance)";
    size_t at = source.find(guarded);
    REQUIRE_MESSAGE(at != std::string::npos, "trace.comp no longer guards radiance this way");
    REQUIRE(source.find(guarded, at + 1) == std::string::npos);
    source.replace(at, guarded.size(), "radiance");
    std::ofstream(copy / "trace.comp") << source;
    return ShaderCompiler(copy, RT_TEST_SHADER_CACHE);
  }();
  return compiler;
}

}  // namespace rt::test
