// The one way the glTF loader includes tinygltf, so that every translation
// unit sees the same configuration: no stb (images stay encoded and are
// decoded by io/Image through our callback), no external image files (the
// loader resolves and reads those itself, only when a material uses them).
#pragma once

#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif

// The includes must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#include <tiny_gltf.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on
