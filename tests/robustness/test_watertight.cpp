// Watertight ray/triangle intersection (shaders/intersect.glsl, through the
// batch kernel shaders/intersect_batch.comp): rays aimed exactly at the
// shared edges and vertices of closed meshes never slip between triangles.
#include <doctest/doctest.h>

#include <map>
#include <random>
#include <set>

#include "formats/ply/PlyLoader.hpp"
#include "render/BatchIntersector.hpp"
#include "robustness/RobustnessSupport.hpp"

using namespace rt;
using namespace rt::test;
using dvec3 = glm::dvec3;

namespace {

// A point where triangles meet: a vertex or an edge's midpoint (rounded to
// float, so within rounding of the edge), with the normals of the triangles
// around it.
struct Face {
  dvec3 a, b, c;
  dvec3 normal() const { return glm::normalize(glm::cross(b - a, c - a)); }
};

struct SharedPoint {
  glm::vec3 position;
  std::vector<Face> faces;  // the triangles around it
};

// Every vertex and edge midpoint, skipping boundary edges and their
// vertices (open meshes such as the scanned bunny).
std::vector<SharedPoint> sharedPoints(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<Face>> edgeFaces;
  std::vector<std::vector<Face>> vertexFaces(mesh.positions.size());
  for (const glm::uvec3& f : mesh.faces) {
    Face face{dvec3(mesh.positions[f.x]), dvec3(mesh.positions[f.y]), dvec3(mesh.positions[f.z])};
    for (auto [from, to] : {std::pair{f.x, f.y}, std::pair{f.y, f.z}, std::pair{f.z, f.x}}) {
      edgeFaces[std::minmax(from, to)].push_back(face);
      vertexFaces[from].push_back(face);
    }
  }
  std::set<uint32_t> boundaryVertices;
  for (const auto& [edge, faces] : edgeFaces) {
    if (faces.size() != 2) boundaryVertices.insert({edge.first, edge.second});
  }
  std::vector<SharedPoint> points;
  for (uint32_t v = 0; v < mesh.positions.size(); ++v) {
    if (!boundaryVertices.count(v)) points.push_back({mesh.positions[v], vertexFaces[v]});
  }
  for (const auto& [edge, faces] : edgeFaces) {
    if (faces.size() != 2) continue;
    points.push_back({0.5f * (mesh.positions[edge.first] + mesh.positions[edge.second]), faces});
  }
  return points;
}

// Whether the ray meets the triangle, in double precision, with a margin of
// 1e-9 in barycentric coordinates (so it meets at least one of the triangles
// around a vertex it is aimed at).
bool meets(const Face& f, dvec3 origin, dvec3 direction) {
  dvec3 e1 = f.b - f.a, e2 = f.c - f.a, p = glm::cross(direction, e2);
  double det = glm::dot(e1, p);
  if (det == 0) return false;
  dvec3 s = origin - f.a, q = glm::cross(s, e1);
  double u = glm::dot(s, p) / det, v = glm::dot(direction, q) / det;
  const double margin = 1e-9;
  return u >= -margin && v >= -margin && u + v <= 1 + margin;
}

// The ray crosses the surface at the point: it meets every triangle around
// the point from the same side, not at a grazing angle (otherwise a point a
// rounding error off a silhouette edge may rightly be missed), and in exact
// arithmetic it meets one of them (scanned meshes have folds and repeated
// faces whose edges count as shared but do not close the surface).
bool crossesThere(const SharedPoint& point, dvec3 origin, dvec3 direction) {
  size_t front = 0, back = 0, met = 0;
  for (const Face& face : point.faces) {
    double cosine = glm::dot(face.normal(), direction);
    front += cosine < -0.05;
    back += cosine > 0.05;
    met += meets(face, origin, direction);
  }
  return (front == point.faces.size() || back == point.faces.size()) && met > 0;
}

Scene meshScene(TriangleMesh mesh) {
  Scene scene;
  addMesh(scene, std::move(mesh), matte(glm::vec3(0.5f)));
  return scene;
}

struct Crossings {
  size_t rays = 0;
  size_t passed = 0;  // no hit, or a first hit beyond the point aimed at
};

// Rays from `origins` (cycled) to each point where they cross the surface.
Crossings aimAt(const Scene& scene, const std::vector<SharedPoint>& points,
                const std::vector<glm::vec3>& origins) {
  std::vector<gpu::GpuRay> rays;
  std::vector<double> targetDistance;
  for (size_t i = 0; i < points.size(); ++i) {
    glm::vec3 from = origins[i % origins.size()];
    dvec3 direction = glm::normalize(dvec3(points[i].position) - dvec3(from));
    if (!crossesThere(points[i], dvec3(from), direction)) continue;
    rays.push_back({from, 0.0f, glm::vec3(direction), 3e38f});
    targetDistance.push_back(glm::length(dvec3(points[i].position) - dvec3(from)));
  }
  BatchIntersector intersector(rt::test::gpu(), shaderCompiler(), scene);
  std::vector<gpu::GpuHit> hits = intersector.intersect(rays);
  Crossings result{rays.size(), 0};
  for (size_t i = 0; i < hits.size(); ++i) {
    result.passed += hits[i].t < 0 || double(hits[i].t) > targetDistance[i] * (1 + 1e-4);
  }
  return result;
}

std::vector<glm::vec3> pointsAround(dvec3 center, double radius, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::vector<glm::vec3> points;
  for (size_t i = 0; i < count; ++i) {
    dvec3 d(gauss(rng), gauss(rng), gauss(rng));
    points.push_back(glm::vec3(center + radius * glm::normalize(d)));
  }
  return points;
}

}  // namespace

TEST_SUITE("robustness-watertight") {
  TEST_CASE("closed icospheres: rays to every shared vertex and edge hit, from inside and out") {
    for (double scale : {1e-3, 1.0, 1e4}) {
      for (dvec3 offset : {dvec3(0), dvec3(0.3, -2.7, 1.1)}) {
        CAPTURE(scale);
        CAPTURE(offset.y);
        dvec3 center = scale * offset;
        TriangleMesh mesh = placed(icosphere(4), scale, center);
        std::vector<SharedPoint> points = sharedPoints(mesh);
        REQUIRE(points.size() == mesh.positions.size() + mesh.faces.size() * 3 / 2);
        Scene scene = meshScene(mesh);
        Crossings inside = aimAt(scene, points, {glm::vec3(center)});
        CHECK(inside.rays == points.size());
        CHECK(inside.passed == 0);
        Crossings outside = aimAt(scene, points, pointsAround(center, 3 * scale, 97, 1));
        CHECK(outside.rays > points.size() * 3 / 4);
        CHECK(outside.passed == 0);
      }
    }
    checkNoValidationMessages();
  }

  TEST_CASE("the Stanford bunny: rays to every interior vertex and edge hit it" * needsShared()) {
    const std::filesystem::path shared = requireShared();
    TriangleMesh bunny =
        loadPly(shared / "assets/ply/stanford-bunny/bunny/reconstruction/bun_zipper.ply");
    std::vector<SharedPoint> points = sharedPoints(bunny);
    dvec3 center(-0.0168, 0.110, -0.0015);
    Crossings crossings = aimAt(meshScene(bunny), points, pointsAround(center, 0.3, 1009, 2));
    MESSAGE(crossings.rays, " rays at bunny vertices and edges, ", crossings.passed,
            " passed through");
    CHECK(crossings.rays > 100000);
    CHECK(crossings.passed == 0);
    checkNoValidationMessages();
  }
}
