// Shared pieces of the test suite: where the shared data lives, one Vulkan
// context with the validation layer on, and the shader compiler.
#pragma once

#include <filesystem>
#include <optional>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "io/Image.hpp"

namespace rt::test {

// ../shared beside the checkout, or nullopt (tests that need it then skip
// with a message, so a clone without it still passes).
std::optional<std::filesystem::path> sharedDir();

// One context for the whole run, validation layer enabled.
VulkanContext& gpu();
const ShaderCompiler& shaderCompiler();

// Fails the current test if the validation layer said anything since the
// last call.
void checkNoValidationMessages();

// Peak signal-to-noise ratio of two same-sized 8-bit images, in dB.
double psnr(const Image8& a, const Image8& b);

// Writes an 8-bit image into the test output folder, for looking at.
void savePng(const Image8& image, const std::string& name);

// Box-filter downscale to the given size (for comparing with small figures).
Image8 downscale(const Image8& image, uint32_t width, uint32_t height);

}  // namespace rt::test
