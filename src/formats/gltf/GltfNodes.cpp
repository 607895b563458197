#include "formats/gltf/GltfNodes.hpp"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "formats/gltf/GltfAccessor.hpp"

namespace rt::gltf {
namespace {

void checkIndex(const Context& context, int index, size_t size, const char* what,
                const std::string& where) {
  if (index < -1 || (index >= 0 && size_t(index) >= size)) {
    context.fail(where, std::string(what) + " " + std::to_string(index) +
                            " does not exist (the file has " + std::to_string(size) + ")");
  }
}

// parent[i] is the one node that lists i as a child, or -1.
std::vector<int> parentsOf(const Context& context) {
  const auto& nodes = context.model().nodes;
  std::vector<int> parent(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const tinygltf::Node& node = nodes[i];
    std::string where = item("nodes", i);
    checkIndex(context, node.mesh, context.model().meshes.size(), "mesh", where + ".mesh");
    checkIndex(context, node.camera, context.model().cameras.size(), "camera", where + ".camera");
    for (size_t k = 0; k < node.children.size(); ++k) {
      int child = node.children[k];
      std::string childWhere = where + "." + item("children", k);
      if (child < 0 || size_t(child) >= nodes.size()) {
        context.fail(childWhere, "node " + std::to_string(child) +
                                     " does not exist (the file has " +
                                     std::to_string(nodes.size()) + ")");
      }
      if (parent[size_t(child)] >= 0) {
        context.fail(childWhere, "node " + std::to_string(child) + " is already a child of " +
                                     item("nodes", parent[size_t(child)]) +
                                     " (glTF node hierarchies must be trees)");
      }
      parent[size_t(child)] = int(i);
    }
  }
  return parent;
}

// With one parent per node, a cycle is a walk up the parent links that comes
// back to a node of the same walk.
void rejectCycles(const Context& context, const std::vector<int>& parent) {
  enum : uint8_t { Unseen, OnWalk, Done };
  std::vector<uint8_t> state(parent.size(), Unseen);
  for (size_t start = 0; start < parent.size(); ++start) {
    int node = int(start);
    while (node >= 0 && state[size_t(node)] == Unseen) {
      state[size_t(node)] = OnWalk;
      node = parent[size_t(node)];
    }
    if (node >= 0 && state[size_t(node)] == OnWalk) {
      context.fail(item("nodes", node), "is its own ancestor (the node hierarchy has a cycle)");
    }
    for (node = int(start); node >= 0 && state[size_t(node)] == OnWalk;) {
      state[size_t(node)] = Done;
      node = parent[size_t(node)];
    }
  }
}

void checkFinite(const Context& context, const std::vector<double>& values, size_t expected,
                 const std::string& where) {
  if (values.size() != expected) {
    context.fail(where, "has " + std::to_string(values.size()) + " numbers, " +
                            std::to_string(expected) + " are required");
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      context.fail(where + "[" + std::to_string(i) + "]", "is not a finite number");
    }
  }
}

glm::dmat4 matrixTransform(const Context& context, const std::vector<double>& m,
                           const std::string& where) {
  checkFinite(context, m, 16, where);
  glm::dmat4 out;
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) out[column][row] = m[size_t(column * 4 + row)];
  }
  const double tolerance = 1e-6;
  bool affine = std::abs(out[0][3]) < tolerance && std::abs(out[1][3]) < tolerance &&
                std::abs(out[2][3]) < tolerance && std::abs(out[3][3] - 1.0) < tolerance;
  if (!affine) context.fail(where, "is not an affine transform (last row must be 0 0 0 1)");
  out[0][3] = out[1][3] = out[2][3] = 0.0;
  out[3][3] = 1.0;
  return out;
}

glm::dmat4 trsTransform(const Context& context, const tinygltf::Node& node,
                        const std::string& where) {
  glm::dmat4 out(1.0);
  if (!node.translation.empty()) {
    checkFinite(context, node.translation, 3, where + ".translation");
    out = glm::translate(out,
                         glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    checkFinite(context, node.rotation, 4, where + ".rotation");
    const auto& r = node.rotation;  // x, y, z, w
    glm::dquat q(r[3], r[0], r[1], r[2]);
    double length = glm::length(q);
    if (!(length > 1e-12)) context.fail(where + ".rotation", "is a zero quaternion");
    out *= glm::mat4_cast(q / length);
  }
  if (!node.scale.empty()) {
    checkFinite(context, node.scale, 3, where + ".scale");
    out = glm::scale(out, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return out;
}

// One EXT_mesh_gpu_instancing attribute: `components` floats per instance,
// or none when absent. All present attributes must agree on the count.
std::vector<float> instanceAttribute(Context& context, const tinygltf::Value& attributes,
                                     const char* name, AccessorUse use, const std::string& where,
                                     size_t& count) {
  if (!attributes.Has(name)) return {};
  const tinygltf::Value& accessor = attributes.Get(name);
  std::string path = where + "." + name;
  if (!accessor.IsInt()) context.fail(path, "expected an accessor index");
  int index = accessor.GetNumberAsInt();
  size_t n = accessorCount(context, index, path);
  if (count != 0 && n != count) {
    context.fail(path, "accessor " + std::to_string(index) + " has " + std::to_string(n) +
                           " elements, the other attributes " + std::to_string(count));
  }
  count = n;
  return readFloats(context, index, use, path);
}

}  // namespace

void validateNodeGraph(const Context& context) { rejectCycles(context, parentsOf(context)); }

std::vector<int> sceneRoots(Context& context) {
  const tinygltf::Model& model = context.model();
  int sceneIndex = model.defaultScene;
  if (sceneIndex >= 0 && size_t(sceneIndex) >= model.scenes.size()) {
    context.fail("scene", "scene " + std::to_string(sceneIndex) + " does not exist (the file has " +
                              std::to_string(model.scenes.size()) + ")");
  }
  std::vector<int> parent = parentsOf(context);
  if (model.scenes.empty()) {
    std::vector<int> roots;
    for (size_t i = 0; i < parent.size(); ++i) {
      if (parent[i] < 0) roots.push_back(int(i));
    }
    if (!roots.empty()) context.warn("scenes", "the file has no scene; drawing every root node");
    return roots;
  }
  if (sceneIndex < 0) sceneIndex = 0;
  const std::vector<int>& roots = model.scenes[size_t(sceneIndex)].nodes;
  std::vector<bool> listed(parent.size(), false);
  for (size_t k = 0; k < roots.size(); ++k) {
    std::string where = item("scenes", sceneIndex) + "." + item("nodes", k);
    int node = roots[k];
    if (node < 0 || size_t(node) >= parent.size()) {
      context.fail(where, "node " + std::to_string(node) + " does not exist (the file has " +
                              std::to_string(parent.size()) + ")");
    }
    if (parent[size_t(node)] >= 0) {
      context.fail(where, "node " + std::to_string(node) +
                              " is not a root node (it is a child of " +
                              item("nodes", parent[size_t(node)]) + ")");
    }
    if (listed[size_t(node)])
      context.fail(where, "node " + std::to_string(node) + " is listed twice");
    listed[size_t(node)] = true;
  }
  return roots;
}

glm::dmat4 localTransform(const Context& context, int index) {
  const tinygltf::Node& node = context.model().nodes[size_t(index)];
  std::string where = item("nodes", index);
  if (!node.matrix.empty()) return matrixTransform(context, node.matrix, where + ".matrix");
  return trsTransform(context, node, where);
}

}  // namespace rt::gltf

namespace rt::gltf {

std::vector<glm::dmat4> instanceTransforms(Context& context, int index) {
  const tinygltf::Node& node = context.model().nodes[size_t(index)];
  auto found = node.extensions.find("EXT_mesh_gpu_instancing");
  if (found == node.extensions.end()) return {glm::dmat4(1.0)};
  std::string where = item("nodes", index) + ".extensions.EXT_mesh_gpu_instancing.attributes";
  const tinygltf::Value& ext = found->second;
  if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject()) {
    context.fail(where, "expected an object of accessor indices");
  }
  const tinygltf::Value& attributes = ext.Get("attributes");
  size_t count = 0;
  auto t = instanceAttribute(context, attributes, "TRANSLATION", AccessorUse::Vec3, where, count);
  auto r = instanceAttribute(context, attributes, "ROTATION", AccessorUse::Vec4, where, count);
  auto s = instanceAttribute(context, attributes, "SCALE", AccessorUse::Vec3, where, count);
  if (count == 0) context.fail(where, "none of TRANSLATION, ROTATION, SCALE is given");
  context.charge(uint64_t(count) * sizeof(glm::dmat4), where);
  std::vector<glm::dmat4> out(count, glm::dmat4(1.0));
  for (size_t i = 0; i < count; ++i) {
    glm::dmat4& m = out[i];
    if (!t.empty()) m = glm::translate(m, glm::dvec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
    if (!r.empty()) {
      glm::dquat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
      double length = glm::length(q);
      if (!(length > 1e-12) || !std::isfinite(length)) {
        context.fail(where + ".ROTATION", "instance " + std::to_string(i) + " is not a rotation");
      }
      m *= glm::mat4_cast(q / length);
    }
    if (!s.empty()) m = glm::scale(m, glm::dvec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
  }
  return out;
}

}  // namespace rt::gltf
