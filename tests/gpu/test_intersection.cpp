// The renderer's intersection shaders, run on the GPU through the batch
// kernel, against double-precision references computed here.
#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>
#include <optional>
#include <random>

#include "render/BatchIntersector.hpp"
#include "support/TestSupport.hpp"

using namespace rt;
using dvec3 = glm::dvec3;

namespace {

struct RefHit {
  double t;
  dvec3 normal;  // outward
};

std::optional<RefHit> closer(std::optional<RefHit> a, std::optional<RefHit> b) {
  if (!a) return b;
  if (!b) return a;
  return a->t <= b->t ? a : b;
}

std::optional<RefHit> refSphere(const Sphere& s, dvec3 o, dvec3 d) {
  dvec3 c(s.center);
  dvec3 f = o - c;
  double b = glm::dot(f, d);
  double disc = b * b - (glm::dot(f, f) - double(s.radius) * s.radius);
  if (disc < 0) return std::nullopt;
  for (double t : {-b - std::sqrt(disc), -b + std::sqrt(disc)}) {
    if (t > 0) return RefHit{t, glm::normalize(o + t * d - c)};
  }
  return std::nullopt;
}

std::optional<RefHit> refTriangle(dvec3 v0, dvec3 v1, dvec3 v2, dvec3 o, dvec3 d) {
  dvec3 n = glm::cross(v1 - v0, v2 - v0);
  double denom = glm::dot(n, d);
  if (denom == 0) return std::nullopt;
  double t = glm::dot(n, v0 - o) / denom;
  if (t <= 0) return std::nullopt;
  dvec3 p = o + t * d;
  // Inside when p is on the inner side of all three edges.
  for (auto [a, b] : {std::pair{v0, v1}, std::pair{v1, v2}, std::pair{v2, v0}}) {
    if (glm::dot(glm::cross(b - a, p - a), n) < 0) return std::nullopt;
  }
  return RefHit{t, glm::normalize(n)};
}

std::optional<RefHit> refQuad(const Quad& q, dvec3 o, dvec3 d) {
  return closer(refTriangle(q.v0, q.v1, q.v2, o, d), refTriangle(q.v0, q.v2, q.v3, o, d));
}

std::optional<RefHit> refCylinder(const Cylinder& cyl, dvec3 o, dvec3 d) {
  dvec3 c(cyl.center), axis = glm::normalize(dvec3(cyl.axis));
  double r = cyl.radius, h = cyl.halfHeight;
  std::optional<RefHit> best;
  dvec3 f = o - c;
  dvec3 dp = d - glm::dot(d, axis) * axis, fp = f - glm::dot(f, axis) * axis;
  double a = glm::dot(dp, dp), b = glm::dot(fp, dp), cc = glm::dot(fp, fp) - r * r;
  double disc = b * b - a * cc;
  if (a > 0 && disc >= 0) {
    for (double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a}) {
      if (t > 0 && std::abs(glm::dot(f + t * d, axis)) <= h) {
        best = closer(best, RefHit{t, glm::normalize(fp + t * dp)});
      }
    }
  }
  for (double side : {-1.0, 1.0}) {
    double denom = glm::dot(d, axis);
    if (denom == 0) continue;
    dvec3 capCenter = c + side * h * axis;
    double t = glm::dot(capCenter - o, axis) / denom;
    dvec3 offset = o + t * d - capCenter;
    if (t > 0 && glm::dot(offset, offset) <= r * r) best = closer(best, RefHit{t, side * axis});
  }
  return best;
}

std::optional<RefHit> reference(const Shape& shape, dvec3 o, dvec3 d) {
  if (auto* s = std::get_if<Sphere>(&shape.geometry)) return refSphere(*s, o, d);
  if (auto* t = std::get_if<Triangle>(&shape.geometry))
    return refTriangle(t->v0, t->v1, t->v2, o, d);
  if (auto* q = std::get_if<Quad>(&shape.geometry)) return refQuad(*q, o, d);
  if (auto* c = std::get_if<Cylinder>(&shape.geometry)) return refCylinder(*c, o, d);
  return std::nullopt;
}

Scene sceneOf(std::vector<Geometry> geometries) {
  Scene scene;
  scene.materials.push_back({});
  for (auto& g : geometries) scene.shapes.push_back({g, 0, ""});
  return scene;
}

std::vector<gpu::GpuRay> randomRays(size_t count, uint32_t seed, float targetExtent = 1.5f) {
  return test::raysTowardsOrigin(count, seed, targetExtent);
}

struct Agreement {
  size_t hits = 0;
  size_t hitMissDisagreements = 0;
  size_t distanceErrors = 0;
  size_t normalErrors = 0;
  size_t anyHitErrors = 0;
};

Agreement compare(const Scene& scene, const std::vector<gpu::GpuRay>& rays) {
  BatchIntersector intersector(test::gpu(), test::shaderCompiler(), scene);
  std::vector<gpu::GpuHit> hits = intersector.intersect(rays);
  Agreement result;
  for (size_t i = 0; i < rays.size(); ++i) {
    dvec3 o(rays[i].origin), d = glm::normalize(dvec3(rays[i].direction));
    std::optional<RefHit> ref;
    uint32_t refShape = 0;
    for (uint32_t s = 0; s < scene.shapes.size(); ++s) {
      auto h = reference(scene.shapes[s], o, d);
      if (h && (!ref || h->t < ref->t)) {
        ref = h;
        refShape = s;
      }
    }
    const gpu::GpuHit& gpuHit = hits[i];
    bool gpuFound = gpuHit.t >= 0;
    result.anyHitErrors += (gpuHit.occluded != 0) != gpuFound;
    if (gpuFound != ref.has_value()) {
      ++result.hitMissDisagreements;
      continue;
    }
    if (!ref) continue;
    ++result.hits;
    bool sameShape = gpuHit.shapeIndex == refShape;
    result.distanceErrors +=
        std::abs(gpuHit.t - ref->t) > 1e-4 * std::max(1.0, ref->t) || !sameShape;
    result.normalErrors += sameShape && glm::dot(dvec3(gpuHit.normal), ref->normal) < 0.9999;
  }
  return result;
}

// Float and double disagree only for rays within rounding of a silhouette
// or an edge: allow a handful in ten thousand.
void checkAgreement(const Agreement& a, size_t rays) {
  CAPTURE(a.hits);
  CHECK(a.hits > rays / 10);
  CHECK(a.hitMissDisagreements <= rays / 2000);
  CHECK(a.distanceErrors <= rays / 2000);
  CHECK(a.normalErrors <= rays / 2000);
  CHECK(a.anyHitErrors == 0);
}

}  // namespace

TEST_SUITE("intersection") {
  TEST_CASE("spheres of different sizes") {
    for (float radius : {0.05f, 1.0f, 1.4f}) {
      CAPTURE(radius);
      Scene scene = sceneOf({Sphere{WorldPoint(radius * glm::vec3(0.1f, -0.2f, 0.3f)), radius}});
      auto rays = randomRays(20000, 1, 1.5f * radius);
      checkAgreement(compare(scene, rays), rays.size());
    }
    test::checkNoValidationMessages();
  }

  TEST_CASE("a triangle, from both sides") {
    Scene scene = sceneOf({Triangle{{-1, -1, 0.2f}, {1.2f, -0.8f, -0.1f}, {0, 1.3f, 0}}});
    auto rays = randomRays(20000, 2);
    checkAgreement(compare(scene, rays), rays.size());
    test::checkNoValidationMessages();
  }

  TEST_CASE("a planar quad (split into two triangles on the host)") {
    Scene scene = sceneOf({Quad{{-1, -1, 0}, {1, -1, 0}, {1.2f, 1, 0}, {-0.8f, 1.1f, 0}}});
    auto rays = randomRays(20000, 3);
    checkAgreement(compare(scene, rays), rays.size());
    test::checkNoValidationMessages();
  }

  TEST_CASE("cylinders: side and caps, any axis") {
    for (glm::vec3 axis : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, 2, -0.5f))}) {
      Scene scene = sceneOf({Cylinder{{0.1f, 0, 0}, axis, 0.6f, 0.9f}});
      auto rays = randomRays(20000, 4);
      checkAgreement(compare(scene, rays), rays.size());
    }
    test::checkNoValidationMessages();
  }

  TEST_CASE("BVH traversal finds the same closest hit as brute force") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(-1.4f, 1.4f), size(0.02f, 0.2f);
    std::vector<Geometry> shapes;
    for (int i = 0; i < 400; ++i) {
      glm::vec3 c(pos(rng), pos(rng), pos(rng));
      if (i % 2 == 0) {
        shapes.push_back(Sphere{WorldPoint(c), size(rng)});
      } else {
        glm::vec3 e1(size(rng), size(rng), -size(rng)), e2(-size(rng), size(rng), size(rng));
        shapes.push_back(Triangle{WorldPoint(c), WorldPoint(c + e1), WorldPoint(c + e2)});
      }
    }
    Scene scene = sceneOf(shapes);
    auto rays = randomRays(20000, 6);
    checkAgreement(compare(scene, rays), rays.size());
    test::checkNoValidationMessages();
  }
}
