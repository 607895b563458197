// The samplers of shaders/rng.glsl, run on the GPU through a probe kernel:
// range, determinism, decorrelation and the stratification of Owen-scrambled
// Sobol points.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <set>
#include <vector>

#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu_types.h"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

struct ProbeParams {
  uint32_t samplerKind = RT_SAMPLER_SOBOL;
  uint32_t pixel = 0;
  uint32_t firstSample = 0;
  uint32_t count = 0;
  uint32_t samplesTotal = 0;
  uint32_t dimension = 0;
  uint32_t seed = 0;
  uint32_t subCount = 1;  // points per pixel sample
};

// The shaders plus the probe kernel in one scratch folder.
const ShaderCompiler& probeCompiler() {
  static const ShaderCompiler compiler = [] {
    std::filesystem::path dir = test::scratchShaderDir("probe");
    std::filesystem::copy_file(std::filesystem::path(RT_SOURCE_SHADER_DIR) / ".." / "tests" /
                                   "render" / "sampler_probe.comp",
                               dir / "sampler_probe.comp");
    return ShaderCompiler(dir, RT_TEST_SHADER_CACHE);
  }();
  return compiler;
}

// samplePair(kind, pixel, first + i, total, dimension, seed) for i < count.
std::vector<glm::vec2> probe(const ProbeParams& params) {
  static ComputeKernel kernel(test::gpu(), probeCompiler().compile("sampler_probe.comp", {}),
                              std::vector<uint32_t>{0}, uint32_t(sizeof(ProbeParams)));
  Buffer points(test::gpu(), std::max<size_t>(params.count, 1) * sizeof(glm::vec2),
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  kernel.bind(0, points);
  test::gpu().submitAndWait([&](VkCommandBuffer commands) {
    kernel.recordDispatch(commands, &params, (params.count + 63) / 64);
  });
  std::vector<glm::vec2> out(params.count);
  points.download(out.data(), out.size() * sizeof(glm::vec2));
  test::checkNoValidationMessages();
  return out;
}

// Sobol samples of one replicate (even sample indices when replicate is 0).
std::vector<glm::vec2> sobolReplicate(uint32_t pixel, uint32_t dimension, uint32_t count,
                                      uint32_t replicate = 0, uint32_t seed = 7) {
  ProbeParams params;
  params.samplerKind = RT_SAMPLER_SOBOL | RT_SAMPLER_REPLICATES;
  params.pixel = pixel;
  params.dimension = dimension;
  params.seed = seed;
  params.count = 2 * count;
  std::vector<glm::vec2> all = probe(params);
  std::vector<glm::vec2> half;
  for (uint32_t i = replicate; i < all.size(); i += 2) half.push_back(all[i]);
  return half;
}

// True if every elementary interval [a / 2^i, (a+1) / 2^i) x [b / 2^j, ...)
// with i + j = log2(points.size() / perInterval) holds exactly
// `perInterval` points: a (0, m, 2)-net in base 2 for perInterval = 1.
bool isNet(const std::vector<glm::vec2>& points, uint32_t perInterval) {
  const uint32_t cells = uint32_t(points.size()) / perInterval;
  const int m = int(std::log2(double(cells)));
  for (int i = 0; i <= m; ++i) {
    const uint32_t columns = 1u << i;
    const uint32_t rows = cells / columns;
    std::vector<uint32_t> counts(cells, 0);
    for (glm::vec2 p : points) {
      uint32_t cx = std::min(uint32_t(p.x * float(columns)), columns - 1);
      uint32_t cy = std::min(uint32_t(p.y * float(rows)), rows - 1);
      ++counts[cy * columns + cx];
    }
    if (std::any_of(counts.begin(), counts.end(), [&](uint32_t c) { return c != perInterval; }))
      return false;
  }
  return true;
}

bool inUnitSquare(const std::vector<glm::vec2>& points) {
  return std::all_of(points.begin(), points.end(), [](glm::vec2 p) {
    return p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f;
  });
}

}  // namespace

TEST_SUITE("convergence sampler") {
  TEST_CASE("Sobol samples lie in [0,1)^2 and are a pure function of their inputs") {
    ProbeParams params;
    params.count = 4096;
    params.pixel = 12345;
    params.dimension = 2;
    params.seed = 3;
    std::vector<glm::vec2> a = probe(params);
    CHECK(inUnitSquare(a));
    CHECK(a == probe(params));
    // Starting later gives the same samples for the same indices.
    params.firstSample = 1000;
    params.count = 8;
    std::vector<glm::vec2> later = probe(params);
    CHECK(std::equal(later.begin(), later.end(), a.begin() + 1000));
    // Large sample indices and high dimensions stay in range.
    params.firstSample = 0xfffff000u;
    params.count = 4096;
    params.dimension = 200;
    CHECK(inUnitSquare(probe(params)));
  }

  TEST_CASE("Sobol samples differ between pixels, dimensions, seeds and replicates") {
    auto first = [](uint32_t pixel, uint32_t dimension, uint32_t seed) {
      ProbeParams params;
      params.pixel = pixel;
      params.dimension = dimension;
      params.seed = seed;
      params.count = 64;
      return probe(params);
    };
    std::vector<glm::vec2> base = first(5, 0, 1);
    CHECK(base != first(6, 0, 1));
    CHECK(base != first(5, 2, 1));
    CHECK(base != first(5, 0, 2));
    // Each value appears once: no pixel or dimension repeats another's points.
    std::set<std::pair<float, float>> seen;
    for (uint32_t pixel = 0; pixel < 16; ++pixel) {
      for (uint32_t dimension = 0; dimension < 128; dimension += 2) {
        for (glm::vec2 p : first(pixel, dimension, 1)) seen.insert({p.x, p.y});
      }
    }
    CHECK(seen.size() == 16 * 64 * 64);
  }

  TEST_CASE("each replicate's first 2^k Sobol points form a (0,k,2)-net") {
    for (uint32_t dimension : {0u, 2u, 4u, 62u, 126u}) {
      for (uint32_t pixel : {0u, 1u, 99999u}) {
        for (uint32_t replicate : {0u, 1u}) {
          std::vector<glm::vec2> points = sobolReplicate(pixel, dimension, 1024, replicate);
          for (uint32_t n = 1; n <= 1024; n *= 2) {
            CAPTURE(dimension);
            CAPTURE(pixel);
            CAPTURE(replicate);
            CAPTURE(n);
            CHECK(isNet({points.begin(), points.begin() + n}, 1));
          }
        }
      }
    }
  }

  TEST_CASE("a pixel's first 2^k Sobol samples form a (0,k,2)-net") {
    ProbeParams params;
    params.pixel = 77;
    params.dimension = 4;
    params.count = 2048;
    std::vector<glm::vec2> points = probe(params);
    for (uint32_t n = 1; n <= 2048; n *= 2) {
      CAPTURE(n);
      CHECK(isNet({points.begin(), points.begin() + n}, 1));
    }
  }

  TEST_CASE("with replicates, the first 2^k samples hold two points per elementary interval") {
    ProbeParams params;
    params.samplerKind = RT_SAMPLER_SOBOL | RT_SAMPLER_REPLICATES;
    params.pixel = 77;
    params.dimension = 4;
    for (uint32_t n = 2; n <= 2048; n *= 2) {
      params.count = n;
      CAPTURE(n);
      std::vector<glm::vec2> points = probe(params);
      CHECK(isNet(points, 2));
      if (n >= 64) CHECK_FALSE(isNet(points, 1));  // the halves do not share strata
    }
  }

  TEST_CASE("any Sobol sample count is stratified to the power of two below it") {
    // n points with 2^m <= n < 2^(m+1): every 2^-m interval of either axis
    // holds one or two points of each replicate (a block of 2^m plus part of
    // the next one).
    std::vector<glm::vec2> points = sobolReplicate(4242, 2, 700);
    for (uint32_t n : {3u, 9u, 25u, 100u, 500u, 700u}) {
      uint32_t cells = 1u << uint32_t(std::floor(std::log2(double(n))));
      for (int axis = 0; axis < 2; ++axis) {
        std::vector<uint32_t> counts(cells, 0);
        for (uint32_t i = 0; i < n; ++i) ++counts[uint32_t(points[i][axis] * float(cells))];
        CAPTURE(n);
        CAPTURE(axis);
        CHECK(*std::min_element(counts.begin(), counts.end()) >= 1);
        CHECK(*std::max_element(counts.begin(), counts.end()) <= 2);
      }
    }
  }

  TEST_CASE("sub-points of each replicate's pixel samples form one net together") {
    // 4 shadow-ray points per pixel sample: replicate 0's first 2^k pixel
    // samples give a (0, k+2, 2)-net, and so does replicate 1's.
    ProbeParams params;
    params.samplerKind = RT_SAMPLER_SOBOL | RT_SAMPLER_REPLICATES;
    params.pixel = 31;
    params.dimension = 4096;
    params.subCount = 4;
    params.count = 2 * 64 * 4;  // 64 pixel samples per replicate
    std::vector<glm::vec2> all = probe(params);
    for (uint32_t replicate : {0u, 1u}) {
      std::vector<glm::vec2> points;
      for (uint32_t s = replicate; s < 128; s += 2) {
        points.insert(points.end(), all.begin() + s * 4, all.begin() + s * 4 + 4);
      }
      CAPTURE(replicate);
      CHECK(isNet(points, 1));
      CHECK(isNet({points.begin(), points.begin() + 32}, 1));
    }
    // Jittered: each replicate's sample x sub-points take distinct cells.
    params.samplerKind = RT_SAMPLER_JITTERED | RT_SAMPLER_REPLICATES;
    params.samplesTotal = 8;
    params.count = 8 * 4;
    all = probe(params);
    CHECK(inUnitSquare(all));
    for (uint32_t replicate : {0u, 1u}) {
      std::set<int> cells;
      for (uint32_t s = replicate; s < 8; s += 2) {
        for (uint32_t k = 0; k < 4; ++k) {
          glm::vec2 p = all[s * 4 + k];
          cells.insert(int(p.x * 4) + 4 * int(p.y * 4));  // 16 points: a 4x4 grid
        }
      }
      CHECK(cells.size() == 16);
    }
  }

  TEST_CASE("random points are not stratified: the net test can fail") {
    ProbeParams params;
    params.samplerKind = RT_SAMPLER_RANDOM;
    params.pixel = 77;
    params.count = 256;
    std::vector<glm::vec2> points = probe(params);
    CHECK(inUnitSquare(points));
    CHECK_FALSE(isNet(points, 1));
  }

  TEST_CASE("a power-of-two jittered count fills an exact grid, and both projections") {
    // 2^k samples: 2^ceil(k/2) x 2^floor(k/2) cells, one sample each (no cell
    // left out), and n strata of width 1/n along each axis, one sample each.
    for (uint32_t count : {8u, 32u, 128u}) {
      const uint32_t k = uint32_t(std::log2(double(count)));
      const uint32_t columns = 1u << ((k + 1) / 2), rows = 1u << (k / 2);
      for (uint32_t pixel = 0; pixel < 16; ++pixel) {
        ProbeParams params;
        params.samplerKind = RT_SAMPLER_JITTERED;
        params.pixel = pixel;
        params.count = count;
        params.samplesTotal = count;
        std::vector<glm::vec2> points = probe(params);
        REQUIRE(inUnitSquare(points));
        std::set<uint32_t> cells, xStrata, yStrata;
        for (glm::vec2 p : points) {
          cells.insert(uint32_t(p.x * float(columns)) + columns * uint32_t(p.y * float(rows)));
          xStrata.insert(uint32_t(p.x * float(count)));
          yStrata.insert(uint32_t(p.y * float(count)));
        }
        CAPTURE(count);
        CAPTURE(pixel);
        CHECK(cells.size() == count);
        CHECK(xStrata.size() == count);
        CHECK(yStrata.size() == count);
      }
    }
  }

  TEST_CASE("jittered replicates each take their own strata of their own count") {
    ProbeParams params;
    params.samplerKind = RT_SAMPLER_JITTERED | RT_SAMPLER_REPLICATES;
    params.pixel = 3;
    params.count = 18;
    params.samplesTotal = 18;  // two replicates of 9: a 3x3 grid each
    std::vector<glm::vec2> points = probe(params);
    CHECK(inUnitSquare(points));
    for (uint32_t replicate : {0u, 1u}) {
      std::set<int> cells;
      for (uint32_t i = replicate; i < points.size(); i += 2)
        cells.insert(int(points[i].x * 3) + 3 * int(points[i].y * 3));
      CHECK(cells.size() == 9);
    }
  }
}
