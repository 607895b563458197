// Run-time GLSL -> SPIR-V compilation with glslang. The renderer, the tests
// and the viewer's hot reload all come through here, so per-scene feature
// defines and edited shaders take the same path. Results are cached on disk,
// keyed by the fully expanded source and the defines.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "util/Error.hpp"

namespace rt {

using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

// A compile failure; what() lists "file:line: message" lines, one per error.
class ShaderCompileError : public Error {
 public:
  using Error::Error;
};

struct ShaderCompileOptions {
  bool optimize = false;  // glslang has no optimizer here; kept for the cache key
  bool useCache = true;
};

class ShaderCompiler {
 public:
  // `shaderDir`: where entry points and their includes live.
  // `cacheDir`: where SPIR-V is cached; empty disables the cache.
  ShaderCompiler(std::filesystem::path shaderDir, std::filesystem::path cacheDir);

  std::vector<uint32_t> compile(const std::string& entryFile, const ShaderDefines& defines,
                                const ShaderCompileOptions& options = {}) const;

  // The one string glslang is given: includes inlined, the defines after
  // #version. The cache key is made of it and glslang's version.
  std::string expandedSource(const std::string& entryFile, const ShaderDefines& defines) const;

  const std::filesystem::path& shaderDir() const { return shaderDir_; }

  // The default shader folder: $RT_SHADER_DIR, else the source tree's shaders/.
  static std::filesystem::path defaultShaderDir();
  // The default cache folder: $RT_SHADER_CACHE, else $XDG_CACHE_HOME or ~/.cache.
  static std::filesystem::path defaultCacheDir();

 private:
  std::filesystem::path shaderDir_;
  std::filesystem::path cacheDir_;
};

}  // namespace rt
