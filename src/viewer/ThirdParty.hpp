// GLFW and Dear ImGui headers, included through here so that their warnings
// (old-style casts, shadowing, conversions) stay out of the -Werror build.
#pragma once

#include <vulkan/vulkan.h>

// clang-format off: the includes must stay between the two.
#include "util/ThirdPartyBegin.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "util/ThirdPartyEnd.hpp"
// clang-format on
