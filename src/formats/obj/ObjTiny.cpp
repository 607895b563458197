// tinyobjloader's implementation, compiled once from Debian's header (the
// package ships it header-only with the implementation behind a define).
// The includes must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on
