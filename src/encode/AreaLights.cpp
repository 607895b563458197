#include "encode/AreaLights.hpp"

#include <glm/gtc/constants.hpp>
#include <type_traits>
#include <variant>

#include "util/Error.hpp"

namespace rt {
namespace {

constexpr float kPi = glm::pi<float>();

gpu::GpuEmitter triangleEmitter(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  gpu::GpuEmitter piece{};
  piece.kind = RT_PRIM_TRIANGLE;
  piece.a = glm::vec4(v0, 0.0f);
  piece.b = glm::vec4(v1, 0.0f);
  piece.c = glm::vec4(v2, 0.0f);
  piece.area = 0.5f * glm::length(glm::cross(v1 - v0, v2 - v0));
  return piece;
}

// The pieces of one shape's surface, in GPU coordinates.
struct SurfacePieces {
  std::vector<gpu::GpuEmitter> pieces;

  void addTriangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
    gpu::GpuEmitter piece = triangleEmitter(v0, v1, v2);
    if (!(piece.area > 0.0f)) return;  // degenerate: emits nothing, never sampled
    pieces.push_back(piece);
  }
};

// Radiance times pi, the unit in which Blinn-Phong's kd and ks multiply
// light (the path tracer's cosine-weighted bounce carries kd * colour *
// radiance), of the light's surface seen head on: what makes a ray that
// hits the light see as much light as next-event estimation credits it.
// Point-like emitters of intensity I * lightScale per area A shining in all
// directions give pi I lightScale / (A |cos|) (the shader divides by the
// cosine); a lamp sphere of radius R gives I lightScale / R^2, which lights
// a facing point exactly like the point light at its centre.
// A Lambertian light of the same power emits 2 pi I lightScale / A from
// each face (its radiance, unlike the isotropic one's, needs no cosine).
glm::vec3 emittedRadiance(const AreaLight& light, const Shape& shape, float area,
                          float lightScale) {
  glm::vec3 intensity = 0.5f * (light.diffuseIntensity + light.specularIntensity) * lightScale;
  if (const auto* sphere = std::get_if<Sphere>(&shape.geometry)) {
    return intensity / (sphere->radius * sphere->radius);
  }
  float faces = light.profile == EmissionProfile::Lambertian ? 2.0f : 1.0f;
  return faces * kPi * intensity / area;
}

SurfacePieces piecesOf(const Shape& shape, const Scene& scene, const GpuFrame& frame) {
  SurfacePieces out;
  std::visit(
      [&](const auto& g) {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          gpu::GpuEmitter piece{};
          piece.kind = RT_PRIM_SPHERE;
          piece.a = glm::vec4(frame.point(g.center), g.radius);
          piece.area = 4.0f * kPi * g.radius * g.radius;
          out.pieces.push_back(piece);
        } else if constexpr (std::is_same_v<T, Cylinder>) {
          gpu::GpuEmitter piece{};
          piece.kind = RT_PRIM_CYLINDER;
          piece.a = glm::vec4(frame.point(g.center), g.radius);
          piece.b = glm::vec4(g.axis, g.halfHeight);
          piece.area = 2.0f * kPi * g.radius * (2.0f * g.halfHeight + g.radius);
          out.pieces.push_back(piece);
        } else if constexpr (std::is_same_v<T, Triangle>) {
          out.addTriangle(frame.point(g.v0), frame.point(g.v1), frame.point(g.v2));
        } else if constexpr (std::is_same_v<T, Quad>) {
          out.addTriangle(frame.point(g.v0), frame.point(g.v1), frame.point(g.v2));
          out.addTriangle(frame.point(g.v0), frame.point(g.v2), frame.point(g.v3));
        } else if constexpr (std::is_same_v<T, MeshInstance>) {
          const TriangleMesh& mesh = scene.meshes.at(g.mesh);
          const glm::mat4 placement = frame.transform(g.objectToWorld);
          std::vector<glm::vec3> points;
          points.reserve(mesh.positions.size());
          for (const glm::vec3& p : mesh.positions) {
            points.push_back(glm::vec3(placement * glm::vec4(p, 1.0f)));
          }
          for (const glm::uvec3& face : mesh.faces) {
            out.addTriangle(points[face.x], points[face.y], points[face.z]);
          }
        }
      },
      shape.geometry);
  return out;
}

}  // namespace

FlatAreaLights flattenAreaLights(const Scene& scene, const GpuFrame& frame, float lightScale) {
  FlatAreaLights flat;
  for (const AreaLight& light : scene.areaLights) {
    const Shape& shape = scene.shapes.at(light.shape);
    SurfacePieces surface = piecesOf(shape, scene, frame);
    if (surface.pieces.empty()) {
      throw Error(scene.sourcePath.string() + ": area light on shape " +
                  std::to_string(light.shape) +
                  (shape.label.empty() ? "" : " ('" + shape.label + "')") + " has no area");
    }
    gpu::GpuAreaLight gpuLight{};
    gpuLight.firstEmitter = static_cast<uint32_t>(flat.emitters.size());
    gpuLight.emitterCount = static_cast<uint32_t>(surface.pieces.size());
    gpuLight.samples = light.samples;
    gpuLight.profile = light.profile == EmissionProfile::Lambertian ? RT_EMISSION_LAMBERTIAN
                                                                    : RT_EMISSION_ISOTROPIC;
    double total = 0.0;
    for (const gpu::GpuEmitter& piece : surface.pieces) total += piece.area;
    double running = 0.0;
    for (gpu::GpuEmitter& piece : surface.pieces) {
      running += piece.area;
      piece.cdfEnd = static_cast<float>(running / total);
    }
    surface.pieces.back().cdfEnd = 1.0f;  // no piece may be out of reach by rounding
    gpuLight.area = static_cast<float>(total);
    gpuLight.diffuseIntensity = light.diffuseIntensity;
    gpuLight.specularIntensity = light.specularIntensity;
    flat.emission.push_back(emittedRadiance(light, shape, gpuLight.area, lightScale));
    flat.emitters.insert(flat.emitters.end(), surface.pieces.begin(), surface.pieces.end());
    flat.lights.push_back(gpuLight);
  }
  return flat;
}

}  // namespace rt
