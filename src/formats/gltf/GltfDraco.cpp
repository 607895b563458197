#include "formats/gltf/GltfDraco.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

// The include must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#include <draco/compression/decode.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on

#include "formats/common/Diagnostics.hpp"
#include "formats/gltf/GltfContext.hpp"

namespace rt::gltf {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";
// Decoded data may reach this plus kBudgetPerDracoByte times the compressed
// bytes: Draco's quantized, predicted streams expand 5-20x on real models,
// and a file that reuses one compressed view everywhere must not multiply it.
constexpr uint64_t kBaseBudget = uint64_t(64) << 20;
constexpr uint64_t kBudgetPerDracoByte = 64;

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices are no vertex attributes
  }
}

// The largest value of an integer Draco type, by which glTF's normalized
// integers are divided; 0 for floating-point and boolean data.
double normalizationDivisor(draco::DataType type) {
  switch (type) {
    case draco::DT_INT8: return 127.0;
    case draco::DT_UINT8: return 255.0;
    case draco::DT_INT16: return 32767.0;
    case draco::DT_UINT16: return 65535.0;
    case draco::DT_INT32: return 2147483647.0;
    case draco::DT_UINT32: return 4294967295.0;
    default: return 0.0;
  }
}

// One tinygltf buffer + buffer view + accessor holding `values`, appended to
// the model; returns the accessor's index. The accessor copies `like` (its
// name, min and max) with the new data's layout.
template <typename T>
int appendAccessor(tinygltf::Model& model, const std::vector<T>& values, size_t count,
                   int componentType, const tinygltf::Accessor& like) {
  tinygltf::Buffer buffer;
  buffer.data.resize(values.size() * sizeof(T));
  std::memcpy(buffer.data.data(), values.data(), buffer.data.size());
  tinygltf::BufferView view;
  view.buffer = int(model.buffers.size());
  view.byteLength = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  tinygltf::Accessor accessor = like;
  accessor.bufferView = int(model.bufferViews.size());
  model.bufferViews.push_back(std::move(view));
  accessor.byteOffset = 0;
  accessor.componentType = componentType;
  accessor.normalized = false;
  accessor.count = count;
  accessor.sparse = {};
  model.accessors.push_back(std::move(accessor));
  return int(model.accessors.size() - 1);
}

class DracoDecoder {
 public:
  DracoDecoder(tinygltf::Model& model, const std::string& fileName)
      : model_(model), diagnostics_(fileName) {}

  void decodeAll() {
    for (size_t m = 0; m < model_.meshes.size(); ++m) {
      auto& primitives = model_.meshes[m].primitives;
      for (size_t p = 0; p < primitives.size(); ++p) {
        auto found = primitives[p].extensions.find(kExtension);
        if (found == primitives[p].extensions.end() || !isTriangleMode(primitives[p].mode)) {
          continue;
        }
        where_ = item("meshes", m) + "." + item("primitives", p) + ".extensions." + kExtension;
        decodePrimitive(primitives[p], found->second);
      }
    }
  }

 private:
  static bool isTriangleMode(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    diagnostics_.fail(key.empty() ? where_ : where_ + "." + key, what);
  }

  void charge(uint64_t bytes) {
    uint64_t budget = kBaseBudget + kBudgetPerDracoByte * compressedBytes_;
    if (bytes > budget || decodedBytes_ > budget - bytes) {
      fail("", "the decoded mesh needs more memory than its compressed data justifies (" +
                   std::to_string(kBaseBudget >> 20) + " MiB + " +
                   std::to_string(kBudgetPerDracoByte) + " x the compressed bytes)");
    }
    decodedBytes_ += bytes;
  }

  void decodePrimitive(tinygltf::Primitive& primitive, const tinygltf::Value& extension) {
    const draco::Mesh& mesh = meshOf(extension.Get("bufferView"));
    const tinygltf::Value& attributes = extension.Get("attributes");
    if (!attributes.IsObject()) fail("attributes", "must be an object of Draco attribute ids");
    for (const std::string& name : attributes.Keys()) {
      decodeAttribute(primitive, name, attributes.Get(name), mesh);
    }
    decodeIndices(primitive, mesh);
  }

  // The decoded mesh of a buffer view, decoded on first use.
  const draco::Mesh& meshOf(const tinygltf::Value& viewValue) {
    if (!viewValue.IsInt()) fail("bufferView", "must be the index of a buffer view");
    int view = viewValue.Get<int>();
    if (auto cached = meshes_.find(view); cached != meshes_.end()) return *cached->second;
    if (view < 0 || size_t(view) >= model_.bufferViews.size()) {
      fail("bufferView", "buffer view " + std::to_string(view) + " does not exist (the file has " +
                             std::to_string(model_.bufferViews.size()) + ")");
    }
    const tinygltf::BufferView& bufferView = model_.bufferViews[size_t(view)];
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= model_.buffers.size()) {
      fail("bufferView", "buffer view " + std::to_string(view) + " names buffer " +
                             std::to_string(bufferView.buffer) + ", which does not exist");
    }
    const std::vector<unsigned char>& data = model_.buffers[size_t(bufferView.buffer)].data;
    if (bufferView.byteOffset > data.size() ||
        bufferView.byteLength > data.size() - bufferView.byteOffset) {
      fail("bufferView", "buffer view " + std::to_string(view) + " (bytes " +
                             std::to_string(bufferView.byteOffset) + " + " +
                             std::to_string(bufferView.byteLength) + ") lies outside its buffer (" +
                             std::to_string(data.size()) + " bytes)");
    }
    compressedBytes_ += bufferView.byteLength;
    draco::DecoderBuffer stream;
    stream.Init(reinterpret_cast<const char*>(data.data() + bufferView.byteOffset),
                bufferView.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&stream);
    if (!decoded.ok()) {
      fail("bufferView", "buffer view " + std::to_string(view) +
                             " is no Draco mesh: " + decoded.status().error_msg_string());
    }
    return *(meshes_[view] = std::move(decoded).value());
  }

  void decodeAttribute(tinygltf::Primitive& primitive, const std::string& name,
                       const tinygltf::Value& idValue, const draco::Mesh& mesh) {
    std::string key = "attributes." + name;
    auto target = primitive.attributes.find(name);
    if (target == primitive.attributes.end()) {
      fail(key, "the primitive has no attribute " + name);
    }
    if (target->second < 0 || size_t(target->second) >= model_.accessors.size()) {
      fail(key, "the primitive's accessor " + std::to_string(target->second) + " does not exist");
    }
    if (!idValue.IsInt()) fail(key, "must be a Draco attribute id");
    const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(idValue.Get<int>());
    if (attribute == nullptr) {
      fail(key, "the Draco mesh has no attribute " + std::to_string(idValue.Get<int>()));
    }
    const tinygltf::Accessor& accessor = model_.accessors[size_t(target->second)];
    int components = componentCount(accessor.type);
    if (components != attribute->num_components()) {
      fail(key, "the Draco attribute has " + std::to_string(int(attribute->num_components())) +
                    " components, its accessor " + std::to_string(target->second) + " " +
                    std::to_string(components));
    }
    std::vector<float> values = pointValues(mesh, *attribute, key);
    double divisor = normalizationDivisor(attribute->data_type());
    if (accessor.normalized && !attribute->normalized() && divisor > 0.0) {
      for (float& v : values) v = std::max(float(v / divisor), -1.0f);
    }
    target->second =
        appendAccessor(model_, values, mesh.num_points(), TINYGLTF_COMPONENT_TYPE_FLOAT, accessor);
  }

  // Every point's value, as floats (Draco undoes its quantization here).
  std::vector<float> pointValues(const draco::Mesh& mesh, const draco::PointAttribute& attribute,
                                 const std::string& key) {
    size_t components = size_t(attribute.num_components());
    charge(uint64_t(mesh.num_points()) * components * sizeof(float));
    std::vector<float> values(size_t(mesh.num_points()) * components);
    for (draco::PointIndex point(0); point < mesh.num_points(); ++point) {
      draco::AttributeValueIndex index = attribute.mapped_index(point);
      if (index.value() >= attribute.size() ||
          !attribute.ConvertValue<float>(index, int8_t(components),
                                         values.data() + size_t(point.value()) * components)) {
        fail(key, "point " + std::to_string(point.value()) + " has no readable value");
      }
    }
    return values;
  }

  void decodeIndices(tinygltf::Primitive& primitive, const draco::Mesh& mesh) {
    charge(uint64_t(mesh.num_faces()) * 3 * sizeof(uint32_t));
    std::vector<uint32_t> indices;
    indices.reserve(size_t(mesh.num_faces()) * 3);
    for (draco::FaceIndex face(0); face < mesh.num_faces(); ++face) {
      for (draco::PointIndex point : mesh.face(face)) indices.push_back(point.value());
    }
    tinygltf::Accessor like;
    like.type = TINYGLTF_TYPE_SCALAR;
    primitive.indices =
        appendAccessor(model_, indices, indices.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, like);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;  // Draco decodes any triangle mode to a list
  }

  tinygltf::Model& model_;
  Diagnostics diagnostics_;
  std::string where_;
  std::map<int, std::unique_ptr<draco::Mesh>> meshes_;
  uint64_t compressedBytes_ = 0;
  uint64_t decodedBytes_ = 0;
};

}  // namespace

std::optional<std::string> jsonWithoutDracoIndices(std::string_view json) {
  if (json.find(kExtension) == std::string_view::npos) return std::nullopt;
  nlohmann::json root = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (!root.is_object() || !root.contains("meshes") || !root["meshes"].is_array()) {
    return std::nullopt;
  }
  bool changed = false;
  for (nlohmann::json& mesh : root["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) {
      continue;
    }
    for (nlohmann::json& primitive : mesh["primitives"]) {
      bool compressed = primitive.is_object() && primitive.contains("extensions") &&
                        primitive["extensions"].is_object() &&
                        primitive["extensions"].contains(kExtension);
      if (compressed && primitive.erase("indices") > 0) changed = true;
    }
  }
  if (!changed) return std::nullopt;
  return root.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& fileName) {
  DracoDecoder(model, fileName).decodeAll();
}

}  // namespace rt::gltf
