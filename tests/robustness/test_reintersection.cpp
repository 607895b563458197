// Rays leaving a surface never hit it again (in the spirit of pbrt-v4's
// reintersection tests): random spheres, triangles, quads and cylinders at
// sizes from 1e-8 to 1e8, some far from the origin relative to their size;
// a ray hits each at a random point, and a ray spawned there by the
// renderer's own code (hitPoint, spawnRay in shaders/geometry.glsl, run
// by shaders/spawn_batch.comp) leaves in a random direction.
#include <doctest/doctest.h>

#include <random>

#include "robustness/RobustnessSupport.hpp"
#include "robustness/SpawnProbe.hpp"

using namespace rt;
using namespace rt::test;
using dvec3 = glm::dvec3;

namespace {

enum class Kind { Sphere, Triangle, Quad, Cylinder };

struct Rng {
  std::mt19937_64 engine;
  double uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine);
  }
  dvec3 direction() {
    while (true) {
      dvec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      double length = glm::length(v);
      if (length > 1e-3 && length <= 1) return v / length;
    }
  }
  dvec3 inBox(double halfSize) {
    return {uniform(-halfSize, halfSize), uniform(-halfSize, halfSize),
            uniform(-halfSize, halfSize)};
  }
};

// A shape of size ~`size`, and how to pick a point on it (double precision).
struct TestShape {
  Geometry geometry;
  double size = 1;
  bool closed = false;  // convex and closed: rays going in must reach the far side
  std::function<dvec3(Rng&, dvec3& normal)> surfacePoint;
  // Whether a surface point is near an edge where a ray going in may meet
  // another face right away (a cylinder's rims).
  std::function<bool(dvec3)> nearEdge = [](dvec3) { return false; };
};

TestShape randomShape(Kind kind, Rng& rng) {
  double size = std::pow(10.0, rng.uniform(-8, 8));
  // Half of the shapes sit up to 1000 sizes from the origin, where the float
  // spacing of their coordinates is up to 1000 times coarser.
  dvec3 center = rng.inBox(size);
  if (rng.uniform(0, 1) < 0.5) center += size * std::pow(10.0, rng.uniform(0, 3)) * rng.direction();
  glm::vec3 c(center);
  if (kind == Kind::Sphere) {
    float radius = float(size * rng.uniform(0.05, 1));
    return {Sphere{dvec3(c), radius}, radius, true, [=](Rng& r, dvec3& normal) {
              normal = r.direction();
              return dvec3(c) + double(radius) * normal;
            }};
  }
  if (kind == Kind::Cylinder) {
    glm::vec3 axis(rng.direction());
    float radius = float(size * rng.uniform(0.05, 1));
    float halfHeight = float(size * rng.uniform(0.05, 1));
    dvec3 a = glm::normalize(dvec3(axis));
    TestShape shape{Cylinder{dvec3(c), axis, radius, halfHeight}, std::min(radius, halfHeight),
                    true, [=](Rng& r, dvec3& normal) {
                      dvec3 radial = glm::normalize(glm::cross(a, r.direction()));
                      if (r.uniform(0, 1) < 0.7) {
                        normal = radial;
                        return dvec3(c) + double(radius) * radial +
                               r.uniform(-1, 1) * halfHeight * a;
                      }
                      normal = r.uniform(0, 1) < 0.5 ? a : -a;
                      return dvec3(c) + double(halfHeight) * normal +
                             std::sqrt(r.uniform(0, 1)) * double(radius) * radial;
                    }};
    shape.nearEdge = [=](dvec3 p) {
      double along = glm::dot(p - dvec3(c), a);
      double fromAxis = glm::length(p - dvec3(c) - along * a);
      return std::abs(along) > 0.95 * halfHeight && fromAxis > 0.95 * radius;
    };
    return shape;
  }
  if (kind == Kind::Triangle) {
    glm::vec3 v0(center + rng.inBox(size)), v1(center + rng.inBox(size)),
        v2(center + rng.inBox(size));
    return {Triangle{dvec3(v0), dvec3(v1), dvec3(v2)}, size, false, [=](Rng& r, dvec3& normal) {
              normal = glm::normalize(glm::cross(dvec3(v1) - dvec3(v0), dvec3(v2) - dvec3(v0)));
              double u = r.uniform(0, 1), v = r.uniform(0, 1);
              if (u + v > 1) u = 1 - u, v = 1 - v;
              return dvec3(v0) + u * (dvec3(v1) - dvec3(v0)) + v * (dvec3(v2) - dvec3(v0));
            }};
  }
  dvec3 u = size * rng.uniform(0.2, 1) * rng.direction();
  dvec3 v = size * rng.uniform(0.2, 1) * glm::normalize(glm::cross(u, rng.direction()));
  glm::vec3 q0(center - u - v), q1(center + u - v), q2(center + u + v), q3(center - u + v);
  return {Quad{dvec3(q0), dvec3(q1), dvec3(q2), dvec3(q3)}, size, false,
          [=](Rng& r, dvec3& normal) {
            normal = glm::normalize(glm::cross(u, v));
            return center + r.uniform(-1, 1) * u + r.uniform(-1, 1) * v;
          }};
}

struct Tally {
  size_t probes = 0;
  size_t firstMissed = 0;  // the first ray hit another shape or nothing
  size_t rehits = 0;       // a leaving ray hit the surface it left, near its start
  size_t inwardChecked = 0;
  size_t inwardWrong = 0;  // a ray into a closed shape missed its far side
};

Tally runKind(Kind kind, uint64_t seed, size_t shapeCount, size_t probesPerShape) {
  Rng rng{std::mt19937_64(seed)};
  Scene scene;
  scene.materials.push_back({});
  std::vector<TestShape> shapes;
  for (size_t i = 0; i < shapeCount; ++i) {
    shapes.push_back(randomShape(kind, rng));
    scene.shapes.push_back({shapes.back().geometry, 0, ""});
  }
  std::vector<SpawnQuery> queries;
  std::vector<uint32_t> target;
  std::vector<bool> nearEdge;
  for (uint32_t s = 0; s < shapes.size(); ++s) {
    for (size_t k = 0; k < probesPerShape; ++k) {
      dvec3 normal;
      dvec3 p = shapes[s].surfacePoint(rng, normal);
      // Start near the shape, on the side the normal names for closed shapes.
      dvec3 away = rng.direction();
      if (shapes[s].closed && glm::dot(away, normal) < 0) away = -away;
      dvec3 from = p + shapes[s].size * rng.uniform(0.5, 3) * away;
      gpu::GpuRay first{glm::vec3(from), 0.0f, glm::vec3(glm::normalize(p - from)), 3e38f};
      queries.push_back({first, glm::vec3(rng.direction())});
      target.push_back(s);
      nearEdge.push_back(shapes[s].nearEdge(p));
    }
  }
  SpawnProbe probe(rt::test::gpu(), shaderCompiler(), scene);
  std::vector<SpawnResult> results = probe.run(queries);
  Tally tally;
  for (size_t i = 0; i < results.size(); ++i) {
    const SpawnResult& r = results[i];
    const TestShape& shape = shapes[target[i]];
    if (r.first.t < 0 || r.first.shapeIndex != target[i]) {
      ++tally.firstMissed;
      continue;
    }
    ++tally.probes;
    dvec3 normal = glm::normalize(dvec3(r.first.normal));
    dvec3 leaving = glm::normalize(dvec3(queries[i].leaving));
    bool sameShape = r.spawned.t >= 0 && r.spawned.shapeIndex == target[i];
    double cosine = glm::dot(leaving, normal);
    if (!shape.closed || cosine > 0) {
      tally.rehits += sameShape;
      continue;
    }
    // Into a closed convex shape: something must be hit (at the latest its
    // far side), and not the shape itself right at the start (except near a
    // rim, where the other face may really be that close).
    if (nearEdge[i]) continue;
    ++tally.inwardChecked;
    bool farSide = r.spawned.t >= 0 && !(sameShape && double(r.spawned.t) < 1e-3 * shape.size);
    tally.inwardWrong += !farSide;
  }
  return tally;
}

}  // namespace

TEST_SUITE("robustness-reintersection") {
  TEST_CASE("rays spawned at hits never hit the surface they left (sizes 1e-8 to 1e8)") {
    struct Case {
      Kind kind;
      const char* name;
    };
    for (Case c : {Case{Kind::Sphere, "spheres"}, Case{Kind::Triangle, "triangles"},
                   Case{Kind::Quad, "quads"}, Case{Kind::Cylinder, "cylinders"}}) {
      CAPTURE(c.name);
      Tally tally = runKind(c.kind, 1000 + uint64_t(c.kind), 96, 64);
      CHECK(tally.probes > 96 * 64 * 8 / 10);
      MESSAGE(std::string(c.name), ": ", tally.probes, " rays spawned, ", tally.rehits,
              " re-hits; ", tally.inwardChecked, " into the shape, ", tally.inwardWrong,
              " not reaching its far side; ", tally.firstMissed, " first rays blocked");

      CHECK(tally.rehits == 0);
      CHECK(tally.inwardWrong == 0);
    }
    checkNoValidationMessages();
  }
}
