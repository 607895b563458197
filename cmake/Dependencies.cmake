# Every dependency comes from a Debian 12 package (scripts/setup.sh installs
# them); nothing is downloaded or vendored.
find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED)
find_package(glslang REQUIRED CONFIG)
find_package(glm REQUIRED CONFIG)
find_package(nlohmann_json REQUIRED CONFIG)
find_package(CLI11 REQUIRED CONFIG)
find_package(fmt REQUIRED CONFIG)
find_package(tinyexr REQUIRED CONFIG)
find_package(draco REQUIRED CONFIG)
# tinyobjloader: header-only use (src/formats/obj/ObjTiny.cpp compiles its
# implementation), so that sanitizer and fuzzer builds instrument it too.
find_path(TINYOBJLOADER_INCLUDE_DIR tiny_obj_loader.h REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
find_package(glfw3 REQUIRED CONFIG)
if(RT_BUILD_TESTS)
  find_package(doctest REQUIRED CONFIG)
endif()
