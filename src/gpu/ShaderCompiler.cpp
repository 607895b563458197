#include "gpu/ShaderCompiler.hpp"

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>
#include <string_view>

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

std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

size_t skipBlanks(std::string_view line, size_t at) {
  while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  return at;
}

// A preprocessor line's directive and its argument ("ifndef", "RT_X"); an
// empty directive for any other line.
struct Directive {
  std::string_view name;
  std::string_view argument;
};

Directive directiveOf(std::string_view line) {
  size_t at = skipBlanks(line, 0);
  if (at == line.size() || line[at] != '#') return {};
  size_t nameStart = skipBlanks(line, at + 1);
  size_t nameEnd = nameStart;
  while (nameEnd < line.size() && std::isalpha(static_cast<unsigned char>(line[nameEnd])))
    ++nameEnd;
  size_t argumentStart = skipBlanks(line, nameEnd);
  size_t argumentEnd = line.size();
  while (argumentEnd > argumentStart &&
         std::isspace(static_cast<unsigned char>(line[argumentEnd - 1]))) {
    --argumentEnd;
  }
  return {line.substr(nameStart, nameEnd - nameStart),
          line.substr(argumentStart, argumentEnd - argumentStart)};
}

// The file named by an `#include "file"` line, or empty.
std::string_view includedFile(const Directive& directive) {
  std::string_view quoted = directive.argument;
  if (directive.name != "include" || quoted.size() < 3 || quoted.front() != '"' ||
      quoted.back() != '"' || quoted.find('"', 1) != quoted.size() - 1) {
    return {};
  }
  return quoted.substr(1, quoted.size() - 2);
}

bool opensBlock(const Directive& directive) {
  return directive.name == "if" || directive.name == "ifdef" || directive.name == "ifndef";
}

// Whether the whole file sits in an include guard: its first directives are
// `#ifndef X` and `#define X`, and the block they open closes at its last one.
// `lineDirectives` holds one entry for each of the file's lines.
bool hasIncludeGuard(const std::vector<Directive>& lineDirectives) {
  std::vector<Directive> directives;
  for (const Directive& directive : lineDirectives) {
    if (!directive.name.empty()) directives.push_back(directive);
  }
  if (directives.size() < 3 || directives[0].name != "ifndef" || directives[1].name != "define" ||
      directives[1].argument.substr(0, directives[1].argument.find_first_of(" \t")) !=
          directives[0].argument) {
    return false;
  }
  int depth = 0;
  for (size_t index = 0; index < directives.size(); ++index) {
    if (opensBlock(directives[index])) ++depth;
    if (directives[index].name == "endif" && --depth == 0) return index + 1 == directives.size();
  }
  return false;
}

// Inlines `#include "file"` lines (relative to the including file) so that
// glslang sees one string, the cache key covers every included file, and
// each line can be mapped back to its file for error messages.
//
// A guarded file is inlined again only where its guard might not be defined
// yet: an earlier copy is known to be compiled wherever it sat in the same
// branches of the same #if blocks as this #include, or in fewer of them.
// Without that, the files that most kernels include reach glslang hundreds of
// times over (12 MB for the trace kernel instead of 217 kB).
class IncludeExpander {
 public:
  explicit IncludeExpander(const std::filesystem::path& root) : root_(root.lexically_normal()) {}

  ExpandedSource expand(const std::string& entryFile) {
    ExpandedSource out;
    expandFile((root_ / entryFile).lexically_normal(), 0, out);
    return out;
  }

 private:
  // The #if blocks around a line, outermost first: each block's number in
  // the expansion and the branch (0 for #if, one more for each #elif/#else).
  using BranchPath = std::vector<std::pair<int, int>>;

  // Returns whether the file has an include guard.
  bool expandFile(const std::filesystem::path& file, int depth, ExpandedSource& out) {
    if (depth > kMaxIncludeDepth) {
      throw ShaderCompileError(
          fmt::format("{}: includes nested too deeply (cycle?)", file.string()));
    }
    const std::string text = readTextFile(file);
    const std::vector<std::string_view> lines = splitLines(text);
    std::vector<Directive> directives;
    for (std::string_view line : lines) directives.push_back(directiveOf(line));
    const bool guarded = hasIncludeGuard(directives);
    std::filesystem::path shown = file.lexically_relative(root_);
    const std::string shownName = shown.empty() ? file.string() : shown.string();
    int fileDepth = 0;  // the file's own #if nesting; a guard's block is not a branch
    for (size_t index = 0; index < lines.size(); ++index) {
      const Directive& directive = directives[index];
      if (std::string_view name = includedFile(directive); !name.empty()) {
        include(file.parent_path() / name, depth, out);
        continue;
      }
      followBlocks(directive, fileDepth, guarded);
      out.text.append(lines[index]);
      out.text += '\n';
      out.origins.push_back({shownName, static_cast<int>(index + 1)});
    }
    return guarded;
  }

  // Keeps branches_ up to date with an #if, #elif, #else or #endif line.
  void followBlocks(const Directive& directive, int& fileDepth, bool guarded) {
    auto inGuardBlock = [&] { return guarded && fileDepth == 1; };
    if (opensBlock(directive)) {
      ++fileDepth;
      if (!inGuardBlock()) {
        branches_.push_back({nextBlock_++, 0});
        blockHasElse_.push_back(false);
      }
    } else if (directive.name == "else" || directive.name == "elif") {
      if (!inGuardBlock() && !branches_.empty()) {
        ++branches_.back().second;
        blockHasElse_.back() = directive.name == "else";
      }
    } else if (directive.name == "endif") {
      if (!inGuardBlock() && !branches_.empty()) closeBlock();
      --fileDepth;
    }
  }

  // A file inlined directly in every branch of an #if ... #else block is
  // compiled whichever branch is taken: after the block it counts as
  // inlined there.
  void closeBlock() {
    const auto [block, lastBranch] = branches_.back();
    const bool hasElse = blockHasElse_.back();
    branches_.pop_back();
    blockHasElse_.pop_back();
    if (!hasElse) return;
    for (auto& [file, copies] : inlined_) {
      int branchesCovered = 0;
      for (int branch = 0; branch <= lastBranch; ++branch) {
        BranchPath inBranch = branches_;
        inBranch.push_back({block, branch});
        branchesCovered += std::find(copies.begin(), copies.end(), inBranch) != copies.end();
      }
      if (branchesCovered == lastBranch + 1) copies.push_back(branches_);
    }
  }

  void include(const std::filesystem::path& file, int depth, ExpandedSource& out) {
    const std::filesystem::path key = file.lexically_normal();
    for (const BranchPath& copy : inlined_[key]) {
      bool enclosing = copy.size() <= branches_.size() &&
                       std::equal(copy.begin(), copy.end(), branches_.begin());
      if (enclosing) return;
    }
    const BranchPath here = branches_;
    if (expandFile(key, depth + 1, out)) inlined_[key].push_back(here);
  }

  std::filesystem::path root_;
  BranchPath branches_;
  std::vector<bool> blockHasElse_;  // one for each of branches_
  int nextBlock_ = 0;
  std::map<std::filesystem::path, std::vector<BranchPath>> inlined_;
};

// Puts the defines right after the #version line, which must stay first.
ExpandedSource withDefines(ExpandedSource source, const ShaderDefines& defines) {
  size_t afterVersion = source.text.find('\n');
  afterVersion = afterVersion == std::string::npos ? source.text.size() : afterVersion + 1;
  std::string lines;
  for (const auto& [name, value] : defines) lines += fmt::format("#define {} {}\n", name, value);
  source.text.insert(afterVersion, lines);
  source.origins.insert(source.origins.begin() + (source.origins.empty() ? 0 : 1), defines.size(),
                        LineOrigin{"<defines>", 0});
  return source;
}

ExpandedSource expandWithDefines(const std::filesystem::path& shaderDir,
                                 const std::string& entryFile, const ShaderDefines& defines) {
  return withDefines(IncludeExpander(shaderDir).expand(entryFile), defines);
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
  ExpandedSource source = expandWithDefines(shaderDir_, entryFile, defines);

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

std::string ShaderCompiler::expandedSource(const std::string& entryFile,
                                           const ShaderDefines& defines) const {
  return expandWithDefines(shaderDir_, entryFile, defines).text;
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
