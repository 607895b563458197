#include "formats/gltf/GltfLoader.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "formats/common/MessageText.hpp"
#include "formats/common/ModelFraming.hpp"
#include "formats/gltf/GltfContext.hpp"
#include "formats/gltf/GltfDocument.hpp"
#include "formats/gltf/GltfDraco.hpp"
#include "formats/gltf/GltfMaterial.hpp"
#include "formats/gltf/GltfMesh.hpp"
#include "formats/gltf/GltfNodes.hpp"
#include "scene/Limits.hpp"

namespace rt {
namespace {

namespace fs = std::filesystem;
using gltf::Context;
using gltf::item;

constexpr float kDirectionalLightRadii = 100.0f;
// World coordinates (vertices, lights, cameras) beyond this are refused:
// whatever is derived from them (framing distance, distant lights at 100
// radii) must still be a finite float.
constexpr double kMaxCoordinate = 1e18;
// Shape labels are for messages; a node name of megabytes is not copied per instance.
constexpr size_t kMaxLabelLength = 80;

using Bounds = WorldBounds;
// glTF cameras: this height, the width from their aspect ratio.
constexpr uint32_t kCameraHeight = 600;
constexpr uint32_t kDefaultCameraWidth = 800;

bool inRange(glm::dvec3 p) {
  return std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
         std::abs(p.z) <= kMaxCoordinate;
}

struct PendingLight {
  WorldPoint position{0.0};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // where a directional light's light travels
  glm::vec3 radiance{1.0f};                // colour * intensity (candela, or lux)
  bool directional = false;
};

// What an import found besides what it added to its scene.
struct ImportResult {
  std::optional<Camera> camera;
  Bounds bounds;  // of the drawn geometry, in world space
};

template <typename Matrix>
bool isFinite(const Matrix& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

glm::dvec3 transformPoint(const glm::dmat4& m, glm::dvec3 p) {
  return glm::dvec3(m * glm::dvec4(p, 1.0));
}

glm::dvec3 transformDirection(const glm::dmat4& m, glm::dvec3 d) {
  return glm::dvec3(m * glm::dvec4(d, 0.0));
}

// A placement that squashes some axis to (nearly) nothing: there is no area
// to draw, and the renderer could not invert it (in float) for the normals.
bool isCollapsed(const glm::dmat4& world, const glm::mat4& objectToWorld) {
  glm::dmat3 linear(world);
  double scale = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
  if (!(std::abs(glm::determinant(linear)) > 1e-9 * scale)) return true;
  glm::mat3 single(objectToWorld);
  return !std::isnormal(glm::determinant(single)) || !isFinite(glm::mat4(glm::inverse(single)));
}

// Walks the scene's node trees and turns what it finds into scene content.
class Importer {
 public:
  Importer(Context& context, Scene& scene, const fs::path& baseDir, const glm::dmat4& placement)
      : context_(context),
        model_(context.model()),
        scene_(scene),
        materials_(context, scene, baseDir),
        placement_(placement) {}

  ImportResult run() {
    gltf::validateNodeGraph(context_);
    walk(gltf::sceneRoots(context_));
    addLights();
    addEmitters();
    if (!model_.animations.empty()) context_.warn("animations", "ignored; drawn at rest");
    return {camera_, bounds_};
  }

 private:
  // Depth first with an explicit stack (a hierarchy may be a long chain), in
  // file order so that "the first camera" is well defined.
  void walk(const std::vector<int>& roots) {
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
      stack.emplace_back(*root, placement_);
    }
    while (!stack.empty()) {
      auto [node, parentWorld] = stack.back();
      stack.pop_back();
      glm::dmat4 world = parentWorld * gltf::localTransform(context_, node);
      if (!isFinite(world)) context_.fail(item("nodes", node), "its world transform overflows");
      visit(node, world);
      const std::vector<int>& children = model_.nodes[size_t(node)].children;
      for (auto child = children.rbegin(); child != children.rend(); ++child) {
        stack.emplace_back(*child, world);
      }
    }
  }

  void visit(int index, const glm::dmat4& world) {
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    if (node.mesh >= 0) placeMesh(index, world);
    if (node.camera >= 0) noteCamera(index, world);
    if (node.extensions.count("KHR_lights_punctual")) noteLight(index, world);
    if (node.skin >= 0) {
      context_.ignored("skins (meshes drawn in their bind pose)", item("nodes", index));
    }
  }

  // The node's mesh, once, or once per EXT_mesh_gpu_instancing instance.
  void placeMesh(int index, const glm::dmat4& world) {
    for (const glm::dmat4& instance : gltf::instanceTransforms(context_, index)) {
      placeMeshOnce(index, world * instance);
    }
  }

  void placeMeshOnce(int index, const glm::dmat4& world) {
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    std::string where = item("nodes", index);
    if (!isFinite(world)) context_.fail(where, "an instance transform is not finite");
    glm::mat4 objectToWorld(world);
    if (!isFinite(objectToWorld)) failOutOfRange(where);
    if (isCollapsed(world, objectToWorld)) {
      context_.ignored("nodes with a zero scale (not drawn)", where);
      return;
    }
    bool mirror = glm::determinant(glm::dmat3(world)) < 0.0;
    const tinygltf::Mesh& mesh = model_.meshes[size_t(node.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      std::optional<uint32_t> meshIndex = sceneMesh(node.mesh, int(p), mirror);
      if (!meshIndex) continue;
      std::string materialWhere =
          item("meshes", node.mesh) + "." + item("primitives", p) + ".material";
      Shape shape;
      shape.label = (node.name.empty() ? where : node.name).substr(0, kMaxLabelLength);
      context_.charge(sizeof(Shape) + shape.label.size(), where);
      shape.geometry = MeshInstance{*meshIndex, world};
      shape.material = materials_.material(mesh.primitives[p].material, materialWhere);
      scene_.shapes.push_back(std::move(shape));
      const glm::vec3 glow = materials_.emission(mesh.primitives[p].material);
      if (glow != glm::vec3(0.0f)) {
        emitters_.push_back({static_cast<uint32_t>(scene_.shapes.size() - 1), glow, where});
      }
      growBounds(*meshIndex, world, where);
    }
  }

  // Scene::meshes index of a glTF primitive, built on first use; mirroring
  // instances get their own copy with reversed winding. nullopt: skipped.
  std::optional<uint32_t> sceneMesh(int mesh, int primitive, bool mirror) {
    auto key = std::make_tuple(mesh, primitive, mirror);
    if (auto found = meshes_.find(key); found != meshes_.end()) return found->second;
    int material = model_.meshes[size_t(mesh)].primitives[size_t(primitive)].material;
    std::optional<TriangleMesh> built =
        gltf::buildPrimitive(context_, mesh, primitive, materials_.uvMapping(material));
    std::optional<uint32_t> index;
    if (built) {
      if (mirror) built = gltf::mirrored(*built);
      Bounds objectBounds;
      for (const glm::vec3& p : built->positions) objectBounds.grow(glm::dvec3(p));
      scene_.meshes.push_back(std::move(*built));
      index = static_cast<uint32_t>(scene_.meshes.size() - 1);
      meshBounds_.emplace(*index, objectBounds);
    }
    meshes_.emplace(key, index);
    return index;
  }

  // The corners of the mesh's object-space box, placed: a bound that costs
  // 8 points per instance whatever the mesh size.
  void growBounds(uint32_t mesh, const glm::dmat4& world, const std::string& where) {
    const Bounds& box = meshBounds_.at(mesh);
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                   corner & 4 ? box.hi.z : box.lo.z);
      glm::dvec3 placed = transformPoint(world, p);
      if (!inRange(placed)) failOutOfRange(where);
      bounds_.grow(placed);
    }
  }

  [[noreturn]] void failOutOfRange(const std::string& where) const {
    context_.fail(where, "places content beyond the supported coordinate range (|x| <= 1e18)");
  }

  void noteCamera(int nodeIndex, const glm::dmat4& world) {
    int index = model_.nodes[size_t(nodeIndex)].camera;
    std::string where = item("cameras", index);
    const tinygltf::Camera& gltfCamera = model_.cameras[size_t(index)];
    if (gltfCamera.type != "perspective") return context_.ignored("orthographic cameras", where);
    if (camera_) return context_.ignored("cameras after the first", where);
    const tinygltf::PerspectiveCamera& lens = gltfCamera.perspective;
    if (!(lens.yfov > 0.0 && lens.yfov < glm::pi<double>())) {
      context_.fail(where + ".perspective.yfov", "must be between 0 and pi radians");
    }
    if (!(lens.aspectRatio >= 0.0 && std::isfinite(lens.aspectRatio))) {
      context_.fail(where + ".perspective.aspectRatio", "must be a positive number");
    }
    glm::dvec3 forward = transformDirection(world, {0.0, 0.0, -1.0});
    glm::dvec3 up = transformDirection(world, {0.0, 1.0, 0.0});
    if (!(glm::length(forward) > 1e-12 && glm::length(up) > 1e-12)) {
      return context_.ignored("cameras on nodes with a zero scale", item("nodes", nodeIndex));
    }
    if (!inRange(glm::dvec3(world[3]))) failOutOfRange(item("nodes", nodeIndex));
    Camera camera;
    camera.height = kCameraHeight;
    camera.width = kDefaultCameraWidth;
    if (lens.aspectRatio > 0.0) {
      double width = std::round(double(kCameraHeight) * lens.aspectRatio);
      camera.width = static_cast<uint32_t>(std::clamp(width, 16.0, double(kMaxImageSide)));
    }
    camera.fovYDegrees = static_cast<float>(glm::degrees(lens.yfov));
    camera.position = WorldPoint(world[3]);
    camera.forward = glm::vec3(glm::normalize(forward));
    camera.up = glm::vec3(glm::normalize(up));
    camera_ = camera;
  }

  glm::vec3 lightColor(const tinygltf::Light& light, const std::string& where) {
    if (light.color.empty()) return glm::vec3(1.0f);
    if (light.color.size() != 3) context_.fail(where + ".color", "must have 3 numbers");
    glm::vec3 color;
    for (int c = 0; c < 3; ++c) {
      double v = light.color[size_t(c)];
      if (!(v >= 0.0 && std::isfinite(v))) {
        context_.fail(where + ".color", "must be finite and not negative");
      }
      color[c] = static_cast<float>(v);
    }
    return color;
  }

  void noteLight(int nodeIndex, const glm::dmat4& world) {
    const tinygltf::Value& ext =
        model_.nodes[size_t(nodeIndex)].extensions.at("KHR_lights_punctual");
    std::string where = item("nodes", nodeIndex) + ".extensions.KHR_lights_punctual.light";
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt()) {
      context_.fail(where, "expected the index of a light");
    }
    int index = ext.Get("light").GetNumberAsInt();
    if (index < 0 || size_t(index) >= model_.lights.size()) {
      context_.fail(where, "light " + std::to_string(index) + " does not exist (the file has " +
                               std::to_string(model_.lights.size()) + ")");
    }
    const tinygltf::Light& light = model_.lights[size_t(index)];
    std::string lightWhere = "extensions.KHR_lights_punctual." + item("lights", index);
    if (!(light.intensity >= 0.0 && std::isfinite(light.intensity))) {
      context_.fail(lightWhere + ".intensity", "must be finite and not negative");
    }
    PendingLight pending;
    pending.radiance = lightColor(light, lightWhere) * static_cast<float>(light.intensity);
    glm::dvec3 position = transformPoint(world, glm::dvec3(0.0));
    if (!inRange(position)) failOutOfRange(item("nodes", nodeIndex));
    pending.position = position;
    if (light.type == "spot") {
      context_.ignored("spot light cones (spot lights shine in all directions)", lightWhere);
    } else if (light.type == "directional") {
      glm::dvec3 direction = transformDirection(world, {0.0, 0.0, -1.0});
      if (!(glm::length(direction) > 1e-12)) {
        return context_.ignored("lights on nodes with a zero scale", item("nodes", nodeIndex));
      }
      context_.ignored("directional lights (placed as distant point lights)", lightWhere);
      pending.direction = glm::vec3(glm::normalize(direction));
      pending.directional = true;
    } else if (light.type != "point") {
      context_.fail(lightWhere + ".type", "'" + light.type + "' is not point, spot or directional");
    }
    lights_.push_back(pending);
  }

  // Photometric intensities have no meaning for a renderer without falloff or
  // units: lights are scaled so that the brightest one's strongest channel is 1.
  void addLights() {
    float brightest = 0.0f;
    for (const PendingLight& light : lights_) {
      brightest = std::max({brightest, light.radiance.x, light.radiance.y, light.radiance.z});
    }
    for (const PendingLight& light : lights_) {
      glm::vec3 intensity = brightest > 0.0f ? light.radiance / brightest : light.radiance;
      WorldPoint position = light.position;
      if (light.directional) {
        position = bounds_.center() -
                   glm::dvec3(light.direction) * (kDirectionalLightRadii * bounds_.radius());
      }
      scene_.pointLights.push_back({position, intensity, intensity});
    }
  }

  // Shapes whose material glows become area lights of its radiance, unless
  // the file has punctual lights: those are normalised to unit lights, in
  // which a radiance has no meaning.
  void addEmitters() {
    if (!emitters_.empty() && !lights_.empty()) {
      context_.ignored("emission beside KHR_lights_punctual lights (the shapes do not light)",
                       emitters_.front().where);
      return;
    }
    for (const PendingEmitter& emitter : emitters_) {
      if (!addRadianceEmitter(scene_, emitter.shape, emitter.radiance)) {
        context_.warn(emitter.where, "glows but has no area to emit from; not a light");
      }
    }
  }

  struct PendingEmitter {
    uint32_t shape;
    glm::vec3 radiance;
    std::string where;
  };

  Context& context_;
  const tinygltf::Model& model_;
  Scene& scene_;
  gltf::MaterialTable materials_;
  std::vector<PendingEmitter> emitters_;
  glm::dmat4 placement_;
  std::map<std::tuple<int, int, bool>, std::optional<uint32_t>> meshes_;
  std::map<uint32_t, Bounds> meshBounds_;
  std::vector<PendingLight> lights_;
  std::optional<Camera> camera_;
  Bounds bounds_;
};

struct Imported {
  Scene scene;
  ImportResult result;
};

Imported importFile(const fs::path& file, const glm::dmat4& placement) {
  return withPrintableErrors([&] {
    Imported out;
    tinygltf::Model model = gltf::readModel(file, out.scene.warnings);
    gltf::decodeDracoPrimitives(model, file.string());
    Context context(file.string(), model);
    Importer importer(context, out.scene, fs::absolute(file).parent_path(), placement);
    out.result = importer.run();
    for (std::string& line : context.takeWarnings()) out.scene.warnings.push_back(std::move(line));
    makePrintable(out.scene.warnings);
    return out;
  });
}

}  // namespace

Scene loadGltfScene(const fs::path& file) {
  Imported imported = importFile(file, glm::dmat4(1.0));
  Scene& scene = imported.scene;
  scene.sourcePath = file;
  const ImportResult& found = imported.result;
  frameModel(scene, found.bounds, found.camera, {"a glTF file", "emissive"});
  if (scene.shapes.empty()) scene.warnings.push_back(file.string() + ": nothing to draw");
  return std::move(imported.scene);
}

void appendGltf(Scene& scene, const fs::path& file, const WorldTransform& placement) {
  // Imported apart and merged at the end: a failing file leaves `scene` as it was.
  Imported imported = importFile(file, placement);
  appendScenePart(scene, std::move(imported.scene));
}

}  // namespace rt
