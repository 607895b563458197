// Include before a third-party header that is compiled into our targets, and
// include util/ThirdPartyEnd.hpp after it: its own warnings are not ours to
// fix, and they must not fail the -Werror build. One list for every such
// header (tinyobjloader, tinygltf, Draco, GLFW, Dear ImGui).
// No include guard: each use opens a new diagnostic scope. Wrap the three
// includes in clang-format off/on, or include sorting moves them apart.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
