// GLFW and Dear ImGui headers, included through here so that their warnings
// (old-style casts, shadowing, conversions) stay out of the -Werror build.
#pragma once

#include <vulkan/vulkan.h>

// The includes must stay between the two (clang-format would sort them).
// clang-format off
#include "util/ThirdPartyBegin.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>
#include "util/ThirdPartyEnd.hpp"
// clang-format on
