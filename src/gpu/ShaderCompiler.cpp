#include "gpu/ShaderCompiler.hpp"

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <cstdlib>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

#include "io/AtomicFile.hpp"

namespace rt {
namespace {

constexpr int kMaxIncludeDepth = 32;

// Where one line of the expanded source came from.
struct LineOrigin {
  std::string file;
  int line = 0;
};

struct ExpandedSource {
  std::string text;
  std::vector<LineOrigin> origins;  // origins[i] is line i + 1 of text
};

std::string readTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ShaderCompileError(fmt::format("{}: cannot open shader file", path.string()));
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

// Inlines `#include "file"` lines (relative to the including file) so that
// glslang sees one string, the cache key covers every included file, and
// each line can be mapped back to its file for error messages.
void expandIncludes(const std::filesystem::path& file, const std::filesystem::path& root, int depth,
                    ExpandedSource& out) {
  if (depth > kMaxIncludeDepth) {
    throw ShaderCompileError(fmt::format("{}: includes nested too deeply (cycle?)", file.string()));
  }
  static const std::regex includeLine(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  std::istringstream lines(readTextFile(file));
  std::string line;
  std::string shownName = std::filesystem::relative(file, root).string();
  for (int number = 1; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch match;
    if (std::regex_match(line, match, includeLine)) {
      expandIncludes(file.parent_path() / match[1].str(), root, depth + 1, out);
      continue;
    }
    out.text += line;
    out.text += '\n';
    out.origins.push_back({shownName, number});
  }
}

// Puts the defines right after the #version line, which must stay first.
ExpandedSource withDefines(const ExpandedSource& source, const ShaderDefines& defines) {
  ExpandedSource result;
  std::istringstream lines(source.text);
  std::string line;
  for (size_t index = 0; std::getline(lines, line); ++index) {
    result.text += line + '\n';
    result.origins.push_back(source.origins[index]);
    if (index != 0) continue;
    for (const auto& [name, value] : defines) {
      result.text += fmt::format("#define {} {}\n", name, value);
      result.origins.push_back({"<defines>", 0});
    }
  }
  return result;
}

// glslang reports "ERROR: NAME:LINE: message" with LINE counted in the
// expanded source; rewrite to "file:line: message" of the original file.
std::string mapDiagnostics(const std::string& log, const std::vector<LineOrigin>& origins) {
  static const std::regex located(R"(^(ERROR|WARNING): [^:]*:(\d+): (.*)$)");
  std::istringstream lines(log);
  std::string line;
  std::string result;
  while (std::getline(lines, line)) {
    std::smatch match;
    if (std::regex_match(line, match, located)) {
      size_t index = std::stoul(match[2].str());
      std::string where =
          index >= 1 && index <= origins.size()
              ? fmt::format("{}:{}", origins[index - 1].file, origins[index - 1].line)
              : "<unknown>";
      std::string level = match[1].str() == "ERROR" ? "error" : "warning";
      result += fmt::format("{}: {}: {}\n", where, level, match[3].str());
    } else if (line.find("compilation errors") == std::string::npos && !line.empty() &&
               line.find("compilation terminated") == std::string::npos) {
      result += line + '\n';
    }
  }
  while (!result.empty() && result.back() == '\n') result.pop_back();
  return result;
}

void initializeGlslangOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    glslang::InitializeProcess();
    std::atexit([] { glslang::FinalizeProcess(); });
  });
}

std::vector<uint32_t> compileToSpirv(const ExpandedSource& source, const std::string& entryFile) {
  initializeGlslangOnce();
  glslang::TShader shader(EShLangCompute);
  const char* text = source.text.c_str();
  const char* names = entryFile.c_str();
  shader.setStringsWithLengthsAndNames(&text, nullptr, &names, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  if (!shader.parse(GetDefaultResources(), 460, false, messages)) {
    throw ShaderCompileError(mapDiagnostics(shader.getInfoLog(), source.origins));
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    throw ShaderCompileError(fmt::format("{}: link error: {}", entryFile, program.getInfoLog()));
  }
  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.generateDebugInfo = false;
  options.disableOptimizer = true;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &options);
  return spirv;
}

uint64_t fnv1a(const std::string& bytes) {
  uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::vector<uint32_t> readCachedSpirv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr uint32_t kSpirvMagic = 0x07230203;
  if (bytes.size() < 20 || bytes.size() % 4 != 0) return {};
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  return words[0] == kSpirvMagic ? words : std::vector<uint32_t>{};
}

}  // namespace

ShaderCompiler::ShaderCompiler(std::filesystem::path shaderDir, std::filesystem::path cacheDir)
    : shaderDir_(std::move(shaderDir)), cacheDir_(std::move(cacheDir)) {}

std::vector<uint32_t> ShaderCompiler::compile(const std::string& entryFile,
                                              const ShaderDefines& defines,
                                              const ShaderCompileOptions& options) const {
  ExpandedSource expanded;
  expandIncludes(shaderDir_ / entryFile, shaderDir_, 0, expanded);
  ExpandedSource source = withDefines(expanded, defines);

  std::filesystem::path cacheFile;
  if (options.useCache && !cacheDir_.empty()) {
    std::string key =
        fmt::format("{}|{}|{}|{}", glslang::GetGlslVersionString(),
                    glslang::GetSpirvGeneratorVersion(), options.optimize, source.text);
    cacheFile = cacheDir_ / fmt::format("{:016x}.spv", fnv1a(key));
    auto cached = readCachedSpirv(cacheFile);
    if (!cached.empty()) return cached;
  }
  std::vector<uint32_t> spirv = compileToSpirv(source, entryFile);
  if (!cacheFile.empty()) {
    // A cache that cannot be written only costs time; never fail the render.
    try {
      std::filesystem::create_directories(cacheDir_);
      writeFileAtomically(cacheFile, spirv.data(), spirv.size() * sizeof(uint32_t));
    } catch (const std::exception&) {
    }
  }
  return spirv;
}

std::filesystem::path ShaderCompiler::defaultShaderDir() {
  if (const char* dir = std::getenv("RT_SHADER_DIR"); dir && *dir) return dir;
  return RT_SOURCE_SHADER_DIR;
}

std::filesystem::path ShaderCompiler::defaultCacheDir() {
  if (const char* dir = std::getenv("RT_SHADER_CACHE"); dir) return dir;  // "" disables
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "raytracer" / "spirv";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "raytracer" / "spirv";
  }
  return {};
}

}  // namespace rt
