// Validated reads of glTF accessors: every index, offset, stride and count is
// checked against the real buffer sizes before a byte is read or an element
// is allocated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats/gltf/GltfContext.hpp"

namespace rt::gltf {

// What a caller accepts from an accessor.
enum class AccessorUse {
  Indices,  // SCALAR of UNSIGNED_BYTE/SHORT/INT, not normalized
  Vec3,     // VEC3 of FLOAT, or of (normalized) 8/16-bit integers (KHR_mesh_quantization)
  Vec2,     // VEC2, same component types
  Vec4,     // VEC4, same component types
};

// The element count of accessor `index`, after checking that it exists.
size_t accessorCount(const Context& context, int index, const std::string& where);

// All elements as floats, `components` per element (4, 3 or 2),
// normalized integers mapped to [0, 1] or [-1, 1], sparse substitutions applied.
std::vector<float> readFloats(Context& context, int index, AccessorUse use,
                              const std::string& where);

// All elements of an index accessor (sparse substitutions applied).
std::vector<uint32_t> readIndices(Context& context, int index, const std::string& where);

}  // namespace rt::gltf
