#include "formats/gltf/GltfAccessor.hpp"

#include <algorithm>
#include <cstring>

namespace rt::gltf {
namespace {

// An accessor without a buffer view is zeros plus sparse substitutions: its
// count is backed by no data, so it is capped instead.
constexpr size_t kMaxUnbackedElements = size_t(1) << 20;

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE exist in tinygltf, not in glTF 2.0
  }
}

std::string componentName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return std::to_string(componentType);
  }
}

std::string typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return std::to_string(type);
  }
}

int expectedType(AccessorUse use) {
  switch (use) {
    case AccessorUse::Indices: return TINYGLTF_TYPE_SCALAR;
    case AccessorUse::Vec2: return TINYGLTF_TYPE_VEC2;
    case AccessorUse::Vec3: return TINYGLTF_TYPE_VEC3;
    case AccessorUse::Vec4: return TINYGLTF_TYPE_VEC4;
  }
  return TINYGLTF_TYPE_SCALAR;
}

int componentsOf(AccessorUse use) {
  switch (use) {
    case AccessorUse::Indices: return 1;
    case AccessorUse::Vec2: return 2;
    case AccessorUse::Vec3: return 3;
    case AccessorUse::Vec4: return 4;
  }
  return 1;
}

bool isIndexComponent(int componentType) {
  return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

bool componentAllowed(AccessorUse use, int componentType) {
  if (use == AccessorUse::Indices) return isIndexComponent(componentType);
  return componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// One component at `bytes` as a number; normalized integers per glTF 2.0
// section 3.11 (signed values clamp at -1).
double decode(const unsigned char* bytes, int componentType, bool normalized) {
  auto load = [bytes](auto value) {
    std::memcpy(&value, bytes, sizeof value);
    return value;
  };
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      double v = load(int8_t{});
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      double v = load(uint8_t{});
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      double v = load(int16_t{});
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      double v = load(uint16_t{});
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(uint32_t{});
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float{});
    default: return 0.0;
  }
}

const tinygltf::Accessor& accessorAt(const Context& context, int index, const std::string& where) {
  const auto& accessors = context.model().accessors;
  if (index < 0 || size_t(index) >= accessors.size()) {
    context.fail(where, "accessor " + std::to_string(index) + " does not exist (the file has " +
                            std::to_string(accessors.size()) + ")");
  }
  return accessors[size_t(index)];
}

struct Bytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

// The bytes of buffer view `viewIndex`, checked to lie inside their buffer.
Bytes viewBytes(const Context& context, int viewIndex, const std::string& where) {
  const tinygltf::Model& model = context.model();
  std::string name = "buffer view " + std::to_string(viewIndex);
  if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size()) {
    context.fail(where, name + " does not exist (the file has " +
                            std::to_string(model.bufferViews.size()) + ")");
  }
  const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
    context.fail(where, name + " refers to buffer " + std::to_string(view.buffer) +
                            ", which does not exist");
  }
  const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    context.fail(where, name + " (bytes " + std::to_string(view.byteOffset) + " + " +
                            std::to_string(view.byteLength) + ") lies outside buffer " +
                            std::to_string(view.buffer) + " (" + std::to_string(data.size()) +
                            " bytes)");
  }
  return {data.data() + view.byteOffset, view.byteLength};
}

// True when `count` elements of `elementSize` bytes, `stride` apart, starting
// at `offset` fit in `size` bytes. No intermediate value can overflow.
bool fits(size_t offset, size_t stride, size_t count, size_t elementSize, size_t size) {
  if (count == 0) return offset <= size;
  if (offset > size || elementSize > size - offset) return false;
  size_t room = size - offset - elementSize;  // what the remaining count - 1 strides may use
  return stride == 0 || (count - 1) <= room / stride;
}

// Where and how an accessor's elements lie, all of it validated.
struct Layout {
  const unsigned char* data = nullptr;  // null: no buffer view, elements are zero
  size_t stride = 0;
  size_t count = 0;
  int componentType = 0;
  int componentBytes = 0;
  int components = 0;
  bool normalized = false;
};

void checkTypes(const Context& context, int index, AccessorUse use, const std::string& where) {
  const tinygltf::Accessor& accessor = context.model().accessors[size_t(index)];
  std::string name = "accessor " + std::to_string(index) + ": ";
  if (componentSize(accessor.componentType) == 0) {
    context.fail(where, name + "componentType " + std::to_string(accessor.componentType) +
                            " is not a glTF 2.0 component type");
  }
  if (accessor.type != expectedType(use)) {
    context.fail(where, name + "type " + typeName(accessor.type) + " where " +
                            typeName(expectedType(use)) + " is required");
  }
  if (!componentAllowed(use, accessor.componentType)) {
    context.fail(where, name + "componentType " + componentName(accessor.componentType) +
                            " is not allowed here");
  }
  bool integer = accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool normalizable = integer && accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (accessor.normalized && (!normalizable || use == AccessorUse::Indices)) {
    context.fail(where, name + "normalized is not allowed with componentType " +
                            componentName(accessor.componentType));
  }
}

// An accessor without a buffer view: zeros that sparse values overwrite.
void checkUnbacked(const Context& context, const tinygltf::Accessor& accessor,
                   const std::string& name, const std::string& where) {
  if (!accessor.sparse.isSparse) {
    context.fail(where, name + " has neither a buffer view nor sparse values");
  }
  if (accessor.count > kMaxUnbackedElements) {
    context.fail(where, name + " has no buffer view and " + std::to_string(accessor.count) +
                            " elements (at most " + std::to_string(kMaxUnbackedElements) +
                            " without a buffer view)");
  }
}

// Sets the stride and the first element, after checking that every element
// lies inside the accessor's buffer view.
void locateInView(const Context& context, const tinygltf::Accessor& accessor,
                  const std::string& name, const std::string& where, Layout& layout) {
  size_t elementSize = size_t(layout.componentBytes) * size_t(layout.components);
  std::string viewName = "buffer view " + std::to_string(accessor.bufferView);
  Bytes view = viewBytes(context, accessor.bufferView, where + ": " + name);
  size_t declaredStride = context.model().bufferViews[size_t(accessor.bufferView)].byteStride;
  layout.stride = declaredStride ? declaredStride : elementSize;
  if (layout.stride < elementSize) {
    context.fail(where, name + ": byteStride " + std::to_string(layout.stride) + " of " + viewName +
                            " is smaller than one element (" + std::to_string(elementSize) +
                            " bytes)");
  }
  if (!fits(accessor.byteOffset, layout.stride, layout.count, elementSize, view.size)) {
    context.fail(where, name + " reads past the end of " + viewName + " (offset " +
                            std::to_string(accessor.byteOffset) + ", " +
                            std::to_string(layout.count) + " elements of " +
                            std::to_string(elementSize) + " bytes every " +
                            std::to_string(layout.stride) + " bytes, view has " +
                            std::to_string(view.size) + " bytes)");
  }
  layout.data = view.data + accessor.byteOffset;
}

Layout layoutOf(const Context& context, int index, AccessorUse use, const std::string& where) {
  const tinygltf::Accessor& accessor = accessorAt(context, index, where);
  std::string name = "accessor " + std::to_string(index);
  checkTypes(context, index, use, where);
  if (accessor.count == 0) context.fail(where, name + " has count 0 (at least 1 is required)");
  Layout layout;
  layout.count = accessor.count;
  layout.componentType = accessor.componentType;
  layout.componentBytes = componentSize(accessor.componentType);
  layout.components = componentsOf(use);
  layout.normalized = accessor.normalized;
  if (accessor.bufferView < 0) {
    checkUnbacked(context, accessor, name, where);
  } else {
    locateInView(context, accessor, name, where, layout);
  }
  return layout;
}

template <typename T>
void readDense(const Layout& layout, std::vector<T>& out) {
  if (!layout.data) return;  // zeros, already there
  size_t n = 0;
  for (size_t i = 0; i < layout.count; ++i) {
    const unsigned char* element = layout.data + i * layout.stride;
    for (int c = 0; c < layout.components; ++c) {
      out[n++] = static_cast<T>(
          decode(element + c * layout.componentBytes, layout.componentType, layout.normalized));
    }
  }
}

// A sparse block's substitutions, validated: `count` indices of
// `indexType` and as many elements laid out like the accessor's, tightly.
struct SparseLayout {
  size_t count = 0;
  int indexType = 0;
  const unsigned char* indices = nullptr;
  const unsigned char* values = nullptr;
};

SparseLayout sparseLayoutOf(const Context& context, const tinygltf::Accessor& accessor,
                            const Layout& layout, const std::string& name,
                            const std::string& where) {
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || size_t(sparse.count) > layout.count) {
    context.fail(where, name + ".count " + std::to_string(sparse.count) + " is not within 1.." +
                            std::to_string(layout.count));
  }
  SparseLayout out{size_t(sparse.count), sparse.indices.componentType, nullptr, nullptr};
  if (!isIndexComponent(out.indexType)) {
    context.fail(where, name + ".indices.componentType " + componentName(out.indexType) +
                            " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  size_t indexBytes = size_t(componentSize(out.indexType));
  size_t elementSize = size_t(layout.componentBytes) * size_t(layout.components);
  Bytes indices = viewBytes(context, sparse.indices.bufferView, where + ": " + name + ".indices");
  Bytes values = viewBytes(context, sparse.values.bufferView, where + ": " + name + ".values");
  if (sparse.indices.byteOffset < 0 ||
      !fits(size_t(sparse.indices.byteOffset), indexBytes, out.count, indexBytes, indices.size)) {
    context.fail(where, name + ".indices read past the end of their buffer view");
  }
  if (sparse.values.byteOffset < 0 ||
      !fits(size_t(sparse.values.byteOffset), elementSize, out.count, elementSize, values.size)) {
    context.fail(where, name + ".values read past the end of their buffer view");
  }
  out.indices = indices.data + sparse.indices.byteOffset;
  out.values = values.data + sparse.values.byteOffset;
  return out;
}

// Overwrites the elements that the accessor's sparse block names.
template <typename T>
void applySparse(const Context& context, int index, const Layout& layout, const std::string& where,
                 std::vector<T>& out) {
  const tinygltf::Accessor& accessor = context.model().accessors[size_t(index)];
  if (!accessor.sparse.isSparse) return;
  std::string name = "accessor " + std::to_string(index) + ": sparse";
  SparseLayout sparse = sparseLayoutOf(context, accessor, layout, name, where);
  size_t indexBytes = size_t(componentSize(sparse.indexType));
  size_t elementSize = size_t(layout.componentBytes) * size_t(layout.components);
  for (size_t k = 0; k < sparse.count; ++k) {
    auto target =
        static_cast<size_t>(decode(sparse.indices + k * indexBytes, sparse.indexType, false));
    if (target >= layout.count) {
      context.fail(where, name + ".indices[" + std::to_string(k) + "] = " + std::to_string(target) +
                              " is not below the accessor's count " + std::to_string(layout.count));
    }
    for (int c = 0; c < layout.components; ++c) {
      out[target * size_t(layout.components) + size_t(c)] = static_cast<T>(
          decode(sparse.values + k * elementSize + size_t(c) * size_t(layout.componentBytes),
                 layout.componentType, layout.normalized));
    }
  }
}

template <typename T>
std::vector<T> readAll(Context& context, int index, AccessorUse use, const std::string& where) {
  Layout layout = layoutOf(context, index, use, where);
  size_t values = layout.count * size_t(layout.components);
  context.charge(uint64_t(values) * sizeof(T), where);
  std::vector<T> out(values, T(0));
  readDense(layout, out);
  applySparse(context, index, layout, where, out);
  return out;
}

}  // namespace

size_t accessorCount(const Context& context, int index, const std::string& where) {
  return accessorAt(context, index, where).count;
}

std::vector<float> readFloats(Context& context, int index, AccessorUse use,
                              const std::string& where) {
  return readAll<float>(context, index, use, where);
}

std::vector<uint32_t> readIndices(Context& context, int index, const std::string& where) {
  return readAll<uint32_t>(context, index, AccessorUse::Indices, where);
}

}  // namespace rt::gltf
