// The one translation unit that compiles tinygltf's implementation.
#define TINYGLTF_IMPLEMENTATION
#include "formats/gltf/GltfDocument.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>
#include <utility>

#include "formats/common/FileBytes.hpp"
#include "formats/common/JsonSyntax.hpp"
#include "formats/gltf/GltfContext.hpp"
#include "formats/gltf/GltfDraco.hpp"
#include "util/Error.hpp"

namespace rt::gltf {
namespace {

namespace fs = std::filesystem;

// Any file the loader reads (the model, its buffers, its images) is read by
// readFileBytes: at most 1 GiB, below the 2^31 that tinygltf's int sizes
// can describe.
static_assert(kMaxInputFileBytes < (uint64_t(1) << 31));
// JSON deeper than this is rejected before parsing: tinygltf converts
// `extras` recursively, so depth would otherwise become stack depth.
constexpr int kMaxJsonDepth = 100;
// Rough memory cost of the parsed document, estimated from the JSON text;
// a few megabytes of "[{},{},...]" would otherwise expand to gigabytes of
// tinygltf structures.
constexpr uint64_t kMaxParsedBytes = uint64_t(2) << 30;

constexpr std::array kSupportedExtensions = {
    "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_volume",  // its thickness makes glass solid; attenuation is ignored
    "KHR_lights_punctual",        "KHR_texture_transform", "KHR_materials_emissive_strength",
    "KHR_materials_unlit",        "KHR_mesh_quantization", "KHR_draco_mesh_compression",
    "EXT_mesh_gpu_instancing",
};

uint32_t readU32(const unsigned char* bytes) {
  return uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 |
         uint32_t(bytes[3]) << 24;
}

void appendU32(std::vector<unsigned char>& out, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(uint8_t(value >> shift));
}

// tinygltf file system callbacks: no "~" expansion, no fallback to the
// working directory (relative candidates are refused), regular files only.
bool fileExists(const std::string& path, void*) {
  std::error_code error;
  return fs::path(path).is_absolute() && fs::is_regular_file(path, error);
}

std::string expandPath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void*) {
  std::string problem = readFileBytes(path, *out);
  if (problem.empty()) return true;
  if (err) *err += problem;
  return false;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported";
  return false;
}

// Image callback: keeps the encoded bytes for later (only images a material
// uses are decoded). tinygltf does not check that an image's buffer view lies
// inside its buffer, so that is checked here before any byte is read; the
// model being filled is the user pointer.
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int,
                      int, const unsigned char* bytes, int size, void* user) {
  const auto* model = static_cast<const tinygltf::Model*>(user);
  image->as_is = true;
  if (image->bufferView < 0) {
    image->image.assign(bytes, bytes + std::max(size, 0));
    return true;
  }
  const tinygltf::BufferView& view = model->bufferViews[size_t(image->bufferView)];
  const std::vector<unsigned char>& data = model->buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    if (err) {
      *err += "images[" + std::to_string(index) + "]: buffer view " +
              std::to_string(image->bufferView) + " lies outside buffer " +
              std::to_string(view.buffer);
    }
    return false;
  }
  auto begin = data.begin() + std::ptrdiff_t(view.byteOffset);
  image->image.assign(begin, begin + std::ptrdiff_t(view.byteLength));
  return true;
}

// tinygltf's messages end lines with '\n'; ours are one line.
std::string oneLine(const std::string& text) {
  std::string out;
  bool pendingBreak = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pendingBreak = !out.empty();
      continue;
    }
    if (pendingBreak) out += "; ";
    pendingBreak = false;
    out += c;
  }
  return out;
}

// tinygltf quotes whole data URIs (megabytes of base64) and other values
// from the file in some messages: data URIs keep their start, and the whole
// message at most kMaxQuotedMessage characters.
constexpr size_t kMaxQuotedMessage = 300;

std::string shortenDataUris(const std::string& text) {
  constexpr size_t kKept = 48;
  std::string out;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t start = text.find("data:", pos);
    if (start == std::string::npos) break;
    size_t end = text.find_first_of(" '\"", start);
    if (end == std::string::npos) end = text.size();
    out.append(text, pos, start - pos);
    if (end - start > kKept + 3) {
      out.append(text, start, kKept);
      out += "...";
    } else {
      out.append(text, start, end - start);
    }
    pos = end;
  }
  out.append(text, std::min(pos, text.size()), std::string::npos);
  if (out.size() > kMaxQuotedMessage) out = out.substr(0, kMaxQuotedMessage - 3) + "...";
  return out;
}

void appendLines(const std::string& fileName, const std::string& text,
                 std::vector<std::string>& lines) {
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty()) lines.push_back(fileName + ": " + shortenDataUris(line));
    start = end + 1;
  }
}

// Walks the JSON text once, outside strings, to bound nesting depth and the
// memory the parsed document will take. Returns what is wrong, or "".
std::string checkJsonShape(std::string_view json) {
  int depth = 0;
  bool inString = false, escaped = false;
  uint64_t estimate = 0;
  std::string_view lastTopKey;
  size_t stringStart = 0;
  for (size_t i = 0; i < json.size(); ++i) {
    char c = json[i];
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
        if (depth == 1) lastTopKey = json.substr(stringStart, i - stringStart);
      }
      continue;
    }
    switch (c) {
      case '"': inString = true, stringStart = i + 1; break;
      case '{':
      case '[':
        if (++depth > kMaxJsonDepth) {
          return "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels";
        }
        // Elements of top-level arrays become tinygltf structs (materials are
        // the largest, about 2 KiB each); other containers are small.
        if (c == '[') {
          estimate += 128;
        } else {
          estimate += depth == 3 && lastTopKey == "materials" ? 2600 : 512;
        }
        break;
      case '}':
      case ']': --depth; break;
      case ',':
      case ':': estimate += 160; break;
      default: break;
    }
  }
  if (estimate > kMaxParsedBytes) {
    return "the JSON would take about " + std::to_string(estimate >> 20) +
           " MiB to parse, more than the " + std::to_string(kMaxParsedBytes >> 20) + " MiB allowed";
  }
  return {};
}

struct GlbChunks {
  std::string_view json;
  const unsigned char* bin = nullptr;
  size_t binSize = 0;
};

// Splits a GLB into its JSON and BIN chunks with exact bounds checks
// (tinygltf's own check lets the BIN chunk end 8 bytes past the data).
GlbChunks splitGlb(const std::vector<unsigned char>& bytes, const std::string& fileName,
                   std::vector<std::string>& warnings) {
  auto fail = [&](const std::string& what) { throw Error(fileName + ": GLB: " + what); };
  if (bytes.size() < 12) fail("header is truncated (" + std::to_string(bytes.size()) + " bytes)");
  uint32_t version = readU32(&bytes[4]);
  if (version != 2) fail("version " + std::to_string(version) + " is not supported (only 2)");
  uint64_t length = readU32(&bytes[8]);
  if (length > bytes.size()) {
    fail("truncated: the header says " + std::to_string(length) + " bytes, the file has " +
         std::to_string(bytes.size()));
  }
  if (length < bytes.size()) {
    warnings.push_back(fileName + ": GLB: " + std::to_string(bytes.size() - length) +
                       " bytes after the declared length are ignored");
  }
  GlbChunks chunks;
  bool haveJson = false;
  uint64_t offset = 12;
  for (int index = 0; offset < length; ++index) {
    std::string where = "chunk " + std::to_string(index) + " at byte " + std::to_string(offset);
    if (length - offset < 8) fail(where + ": header is truncated");
    uint64_t size = readU32(&bytes[offset]);
    uint32_t type = readU32(&bytes[offset + 4]);
    if (size > length - offset - 8) {
      fail(where + ": its " + std::to_string(size) + " bytes run past the end of the file");
    }
    const unsigned char* data = bytes.data() + offset + 8;
    if (index == 0) {
      if (type != 0x4E4F534Au) fail("the first chunk is not JSON");
      chunks.json = std::string_view(reinterpret_cast<const char*>(data), size_t(size));
      haveJson = true;
    } else if (type == 0x4E4F534Au) {
      fail(where + ": a second JSON chunk");
    } else if (type == 0x004E4942u) {
      if (index != 1) fail(where + ": the BIN chunk must be the second chunk");
      chunks.bin = data;
      chunks.binSize = size_t(size);
    }  // chunks of other types are to be ignored (glTF 2.0, 4.4.3.1)
    offset += 8 + size;
  }
  if (!haveJson) fail("no JSON chunk");
  return chunks;
}

// Rebuilds a GLB with exact, padded chunk lengths, which tinygltf reads safely.
std::vector<unsigned char> canonicalGlb(const GlbChunks& chunks) {
  auto padded = [](size_t size) { return (size + 3) & ~size_t(3); };
  size_t jsonSize = padded(chunks.json.size());
  size_t binSize = padded(chunks.binSize);
  size_t total = 12 + 8 + jsonSize + (binSize ? 8 + binSize : 0);
  std::vector<unsigned char> out;
  out.reserve(total);
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  appendU32(out, 2);
  appendU32(out, uint32_t(total));
  appendU32(out, uint32_t(jsonSize));
  appendU32(out, 0x4E4F534Au);
  out.insert(out.end(), chunks.json.begin(), chunks.json.end());
  out.resize(out.size() + jsonSize - chunks.json.size(), ' ');
  if (binSize) {
    appendU32(out, uint32_t(binSize));
    appendU32(out, 0x004E4942u);
    out.insert(out.end(), chunks.bin, chunks.bin + chunks.binSize);
    out.resize(total, 0);
  }
  return out;
}

void checkVersion(const std::string& version, const std::string& minVersion,
                  const std::string& fileName) {
  if (version.rfind("2.", 0) != 0) {
    throw Error(fileName + ": asset.version: glTF '" + version +
                "' is not supported (only glTF 2.x)");
  }
  if (!minVersion.empty() && minVersion != "2.0") {
    throw Error(fileName + ": asset.minVersion: the file needs glTF " + minVersion +
                ", this loader reads glTF 2.0");
  }
}

void checkRequiredExtensions(const std::vector<std::string>& required,
                             const std::string& fileName) {
  for (const std::string& name : required) {
    if (!isSupportedExtension(name)) {
      throw Error(fileName + ": glTF requires extension " + name + ", which is not supported");
    }
  }
}

// A buffer file that cannot be read, named with its index and the reason.
void checkBufferFiles(const nlohmann::json& buffers, const fs::path& baseDir,
                      const std::string& fileName) {
  if (!buffers.is_array()) return;
  for (size_t i = 0; i < buffers.size(); ++i) {
    if (!buffers[i].is_object() || !buffers[i].value("uri", nlohmann::json()).is_string()) continue;
    std::string uri = buffers[i]["uri"];
    if (uri.rfind("data:", 0) == 0) continue;
    fs::path path = baseDir / percentDecoded(uri);
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      throw Error(fileName + ": buffers[" + std::to_string(i) + "]: cannot read '" + uri +
                  "': " + (fs::exists(path, error) ? "not a regular file" : "file not found"));
    }
  }
}

// A non-negative integer member of a JSON object, if it is one.
std::optional<uint64_t> unsignedMember(const nlohmann::json& object, const char* key) {
  if (!object.is_object() || !object.contains(key)) return std::nullopt;
  const nlohmann::json& value = object[key];
  if (!value.is_number_unsigned()) return std::nullopt;
  return value.get<uint64_t>();
}

// tinygltf 2.7 takes the address of an image's buffer-view bytes before our
// callback can check them (an abort under _GLIBCXX_ASSERTIONS); so images
// stored in buffer views are checked first, from a parse that keeps only
// "images", "bufferViews" and "buffers" (without their data URIs). Buffer
// sizes are the declared byteLength, which tinygltf enforces.
void checkImageViews(std::string_view json, const std::string& fileName) {
  auto keepViews = [](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    if (event != nlohmann::json::parse_event_t::key) return true;
    if (depth == 1) return parsed == "images" || parsed == "bufferViews" || parsed == "buffers";
    return parsed != "uri";
  };
  nlohmann::json root = nlohmann::json::parse(json.begin(), json.end(), keepViews, false);
  if (!root.is_object() || !root.contains("images") || !root["images"].is_array()) return;
  const nlohmann::json& views = root.value("bufferViews", nlohmann::json::array());
  const nlohmann::json& buffers = root.value("buffers", nlohmann::json::array());
  const nlohmann::json& images = root["images"];
  for (size_t i = 0; i < images.size(); ++i) {
    std::optional<uint64_t> view = unsignedMember(images[i], "bufferView");
    if (!view || !views.is_array() || *view >= views.size()) continue;
    std::optional<uint64_t> buffer = unsignedMember(views[*view], "buffer");
    if (!buffer || !buffers.is_array() || *buffer >= buffers.size()) continue;
    uint64_t offset = unsignedMember(views[*view], "byteOffset").value_or(0);
    uint64_t length = unsignedMember(views[*view], "byteLength").value_or(0);
    uint64_t size = unsignedMember(buffers[*buffer], "byteLength").value_or(0);
    if (offset > size || length > size - offset) {
      throw Error(fileName + ": images[" + std::to_string(i) + "]: buffer view " +
                  std::to_string(*view) + " (bytes " + std::to_string(offset) + " + " +
                  std::to_string(length) + ") lies outside buffer " + std::to_string(*buffer) +
                  " (" + std::to_string(size) + " bytes)");
    }
  }
}

// tinygltf reports JSON syntax errors as "[json.exception...] parse error at
// line L, column C" (and an empty file as "JSON string too short"); messages
// say where in bytes, as the scene loader's do. A parse that keeps nothing
// finds the offset. `where` names the text: the file, or its GLB JSON chunk.
void checkJsonSyntax(std::string_view json, const std::string& where) {
  if (json.empty()) throw Error(where + ": empty file");
  auto keepNothing = [](int, nlohmann::json::parse_event_t, nlohmann::json&) { return false; };
  withJsonSyntaxErrors(where, json, [&] {
    const nlohmann::json nothing = nlohmann::json::parse(json.begin(), json.end(), keepNothing);
  });
}

// Names of the top-level arrays whose objects tinygltf calls `type` in
// "'<key>' property is missing in <type>." (nested objects are not listed).
std::optional<std::string> arrayOfType(std::string_view type) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 13> kArrays = {{
      {"Accessor", "accessors"},
      {"Animation", "animations"},
      {"Buffer", "buffers"},
      {"BufferView", "bufferViews"},
      {"Camera", "cameras"},
      {"Image", "images"},
      {"Material", "materials"},
      {"Mesh", "meshes"},
      {"Node", "nodes"},
      {"Sampler", "samplers"},
      {"Scene", "scenes"},
      {"Skin", "skins"},
      {"Texture", "textures"},
  }};
  for (const auto& [name, array] : kArrays) {
    if (name == type) return std::string(array);
  }
  return std::nullopt;
}

// The top-level arrays `names` of the document (without data URIs).
nlohmann::json topLevelArrays(std::string_view json, const std::vector<std::string>& names) {
  auto keepArrays = [&names](int depth, nlohmann::json::parse_event_t event,
                             nlohmann::json& parsed) {
    if (event != nlohmann::json::parse_event_t::key) return true;
    if (depth == 1) return std::find(names.begin(), names.end(), parsed) != names.end();
    return parsed != "uri";
  };
  return nlohmann::json::parse(json.begin(), json.end(), keepArrays, false);
}

// The first element of `array` (an array of objects) that `bad` accepts.
template <typename Predicate>
std::optional<size_t> firstElement(const nlohmann::json& root, const std::string& array,
                                   Predicate bad) {
  if (!root.is_object() || !root.contains(array) || !root[array].is_array()) return std::nullopt;
  const nlohmann::json& items = root[array];
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].is_object() && bad(items[i])) return i;
  }
  return std::nullopt;
}

// tinygltf's "'byteLength' property is missing in BufferView." and "'count'
// property is not a positive integer." name no object; when the complaint is
// one of these two, find the first object it fits and say where it is.
void locateComplaint(std::string_view json, const std::string& complaint,
                     const std::string& fileName) {
  const size_t keyEnd = complaint.find("' property is ");
  if (complaint.empty() || complaint[0] != '\'' || keyEnd == std::string::npos) return;
  const std::string key = complaint.substr(1, keyEnd - 1);
  const std::string rest = complaint.substr(keyEnd + 14);
  const std::string missingIn = "missing in ";
  if (rest.rfind(missingIn, 0) == 0 && rest.size() > missingIn.size() && rest.back() == '.') {
    std::string type = rest.substr(missingIn.size(), rest.size() - missingIn.size() - 1);
    std::erase_if(type, [](char c) { return c == '`' || c == '\''; });  // "`Accessor'" too
    const std::optional<std::string> array = arrayOfType(type);
    if (!array) return;
    const nlohmann::json root = topLevelArrays(json, {*array});
    const auto at =
        firstElement(root, *array, [&](const nlohmann::json& o) { return !o.contains(key); });
    if (at)
      throw Error(fileName + ": " + item(array->c_str(), *at) + "." + key + ": missing (required)");
  } else if (rest == "not a positive integer.") {
    const std::vector<std::string> arrays = {"buffers", "bufferViews", "accessors"};
    const nlohmann::json root = topLevelArrays(json, arrays);
    for (const std::string& array : arrays) {
      const auto bad = [&](const nlohmann::json& o) {
        return o.contains(key) && !o[key].is_number_unsigned();
      };
      if (const auto at = firstElement(root, array, bad)) {
        std::string value = root[array][*at][key].dump();
        if (value.size() > 40) value = value.substr(0, 40) + "...";
        throw Error(fileName + ": " + item(array.c_str(), *at) + "." + key +
                    ": must be a non-negative integer, got " + value);
      }
    }
  }
}

// When tinygltf refuses a file, the reason may be a version or a required
// extension that changes what the data means (an unsupported compression's
// accessors have no buffer view, for instance), or a missing buffer file; those make better
// messages. Only "asset", "extensionsRequired" and "buffers" are kept from
// this second parse.
void explainRefusal(std::string_view json, const fs::path& baseDir, const std::string& fileName) {
  auto keepDeclarations = [](int depth, nlohmann::json::parse_event_t event,
                             nlohmann::json& parsed) {
    if (depth != 1 || event != nlohmann::json::parse_event_t::key) return true;
    return parsed == "asset" || parsed == "extensionsRequired" || parsed == "buffers";
  };
  nlohmann::json root = nlohmann::json::parse(json.begin(), json.end(), keepDeclarations, false);
  if (!root.is_object()) return;
  const nlohmann::json& asset = root.value("asset", nlohmann::json::object());
  if (asset.is_object() && asset.value("version", nlohmann::json()).is_string()) {
    checkVersion(asset["version"], asset.value("minVersion", ""), fileName);
  }
  const nlohmann::json& required = root.value("extensionsRequired", nlohmann::json::array());
  for (const nlohmann::json& name : required.is_array() ? required : nlohmann::json::array()) {
    if (name.is_string()) checkRequiredExtensions({name.get<std::string>()}, fileName);
  }
  checkBufferFiles(root.value("buffers", nlohmann::json()), baseDir, fileName);
}

void checkVersionAndExtensions(const tinygltf::Model& model, const std::string& fileName,
                               std::vector<std::string>& warnings) {
  checkVersion(model.asset.version, model.asset.minVersion, fileName);
  checkRequiredExtensions(model.extensionsRequired, fileName);
  for (const std::string& name : model.extensionsUsed) {
    if (!isSupportedExtension(name)) {
      warnings.push_back(fileName + ": uses extension " + name + ", which is ignored");
    }
  }
}

tinygltf::TinyGLTF makeParser(tinygltf::Model& model) {
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &refuseWrite, nullptr});
  parser.SetImageLoader(&keepEncodedImage, &model);
  return parser;
}

}  // namespace

bool isSupportedExtension(const std::string& name) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), name) !=
         kSupportedExtensions.end();
}

namespace {

// The bytes tinygltf will parse: the .gltf text, or a canonical GLB.
struct Source {
  std::vector<unsigned char> bytes;
  std::string_view json;  // inside `bytes`
  bool glb = false;
};

// A source of canonical GLB bytes built from `chunks`.
void setGlb(Source& source, const GlbChunks& chunks) {
  std::vector<unsigned char> canonical = canonicalGlb(chunks);
  size_t jsonSize = chunks.json.size();
  source.bytes.swap(canonical);  // `chunks` may point into the old bytes
  source.json = std::string_view(reinterpret_cast<const char*>(source.bytes.data() + 20), jsonSize);
}

// The same document with its JSON text replaced (and the BIN chunk kept).
void replaceJson(Source& source, const std::string& json, const std::string& fileName) {
  if (source.glb) {
    std::vector<std::string> none;  // a canonical GLB has nothing to warn about
    GlbChunks chunks = splitGlb(source.bytes, fileName, none);
    chunks.json = json;
    setGlb(source, chunks);
  } else {
    source.bytes.assign(json.begin(), json.end());
    source.json =
        std::string_view(reinterpret_cast<const char*>(source.bytes.data()), source.bytes.size());
  }
}

// Reads the file and runs every check that must come before tinygltf.
Source readSource(const fs::path& file, const std::string& fileName,
                  std::vector<std::string>& warnings) {
  Source source;
  if (std::string problem = readFileBytes(file, source.bytes); !problem.empty()) {
    throw Error(fileName + ": " + problem);
  }
  source.glb = source.bytes.size() >= 4 && std::memcmp(source.bytes.data(), "glTF", 4) == 0;
  if (source.glb) {
    setGlb(source, splitGlb(source.bytes, fileName, warnings));
  } else {
    source.json =
        std::string_view(reinterpret_cast<const char*>(source.bytes.data()), source.bytes.size());
  }
  if (std::string problem = checkJsonShape(source.json); !problem.empty()) {
    throw Error(fileName + ": " + problem);
  }
  if (source.json.find("\"images\"") != std::string_view::npos) {
    checkImageViews(source.json, fileName);
  }
  if (std::optional<std::string> json = jsonWithoutDracoIndices(source.json)) {
    replaceJson(source, *json, fileName);
  }
  return source;
}

}  // namespace

tinygltf::Model readModel(const fs::path& file, std::vector<std::string>& warnings) {
  const std::string fileName = file.string();
  Source source = readSource(file, fileName, warnings);
  tinygltf::Model model;
  tinygltf::TinyGLTF parser = makeParser(model);
  std::string baseDir = fs::absolute(file).parent_path().string();
  std::string err, warn;
  bool ok = source.glb ? parser.LoadBinaryFromMemory(&model, &err, &warn, source.bytes.data(),
                                                     unsigned(source.bytes.size()), baseDir)
                       : parser.LoadASCIIFromString(&model, &err, &warn, source.json.data(),
                                                    unsigned(source.json.size()), baseDir);
  if (!ok) {
    checkJsonSyntax(source.json, source.glb ? fileName + ": GLB JSON chunk" : fileName);
    explainRefusal(source.json, baseDir, fileName);
    std::string what = shortenDataUris(oneLine(err.empty() ? warn : err));
    locateComplaint(source.json, what.substr(0, what.find("; ")), fileName);
    throw Error(fileName + ": " + (what.empty() ? "not a valid glTF file" : what));
  }
  appendLines(fileName, warn, warnings);
  appendLines(fileName, err, warnings);  // tinygltf reports some problems it tolerates as errors
  checkVersionAndExtensions(model, fileName, warnings);
  return model;
}

}  // namespace rt::gltf
