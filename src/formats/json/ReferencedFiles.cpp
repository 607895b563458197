#include "formats/json/ReferencedFiles.hpp"

#include <algorithm>
#include <cctype>
#include <system_error>
#include <vector>

#include "formats/common/SceneTextures.hpp"
#include "util/Error.hpp"

namespace rt {

namespace fs = std::filesystem;

namespace {

// Some students ran from a build folder inside the scene's folder
// ("../textures/x.jpg" next to demo.json): the path seen from a subfolder.
fs::path seenFromSubfolder(const fs::path& written, const fs::path& sceneDir) {
  auto part = written.begin();
  if (written.is_absolute() || part == written.end() || *part != "..") return {};
  fs::path rest;
  for (++part; part != written.end(); ++part) rest /= *part;
  return rest.empty() ? fs::path{} : (sceneDir / rest).lexically_normal();
}

// "/Users/x/..." or "C:/Users/x/..." (backslashes already turned around).
bool isAbsoluteAnywhere(const std::string& text) {
  const bool drive = text.size() >= 3 && std::isalpha(static_cast<unsigned char>(text[0])) &&
                     text[1] == ':' && text[2] == '/';
  return drive || fs::path(text).is_absolute();
}

// How many folders above the scene's a moved absolute path is looked for in.
constexpr int kMovedFileLevels = 3;

// An absolute path from the author's machine ("/Users/a/cw/Code/Textures/
// x.ppm") names a file that came with the scene, at the same place under
// some folder: its tails (Code/Textures/x.ppm, Textures/x.ppm, x.ppm),
// longest first, are looked for in the scene's folder and the few above it
// (the bare file name only in the scene's folder: higher up it could be any
// file of that name).
std::optional<fs::path> findMovedFile(const std::string& text, const fs::path& sceneDir) {
  std::vector<fs::path> parts;
  for (const fs::path& part : fs::path(text).relative_path()) parts.push_back(part);
  std::vector<fs::path> folders{sceneDir};
  for (int level = 0; level < kMovedFileLevels && folders.back().has_relative_path(); ++level) {
    folders.push_back(folders.back().parent_path());
  }
  for (size_t first = 1; first < parts.size(); ++first) {
    fs::path tail;
    for (size_t i = first; i < parts.size(); ++i) tail /= parts[i];
    for (const fs::path& folder : folders) {
      if (first + 1 == parts.size() && folder != sceneDir) break;
      std::error_code ignored;
      const fs::path candidate = (folder / tail).lexically_normal();
      if (fs::is_regular_file(candidate, ignored)) return candidate;
    }
  }
  return std::nullopt;
}

}  // namespace

fs::path absoluteFolderOf(const fs::path& file) {
  std::error_code failed;
  const fs::path absolute = fs::absolute(file, failed);
  return (failed ? file : absolute).lexically_normal().parent_path();
}

// Texture paths in family A are relative to a build folder beside examples/,
// so "../textures/x.jpg" works from the scene's own folder; the README also
// allows the folder above it. Students' mesh paths follow the same habit
// ("examples/monkey.ply" from examples/), and some ran from a folder inside
// the scene's. Backslashes (Windows) are folder separators.
std::optional<fs::path> findReferencedFile(const JsonNode& node, const fs::path& sceneDir) {
  std::string text = node.nonEmptyString();
  std::replace(text.begin(), text.end(), '\\', '/');
  const fs::path written = text;
  const fs::path parentDir = sceneDir.parent_path();
  for (const fs::path& candidate :
       {(sceneDir / written).lexically_normal(), (parentDir / written).lexically_normal(),
        seenFromSubfolder(written, sceneDir)}) {
    std::error_code ignored;
    if (!candidate.empty() && fs::is_regular_file(candidate, ignored)) return candidate;
  }
  if (isAbsoluteAnywhere(text)) {
    if (std::optional<fs::path> moved = findMovedFile(text, sceneDir)) {
      node.warn("the absolute path is not on this machine; using " + moved->string() +
                ", found by its tail");
      return moved;
    }
  }
  return std::nullopt;
}

std::string notFoundMessage(const JsonNode& node, const fs::path& sceneDir, std::string_view kind) {
  const fs::path written = node.raw().get<std::string>();
  const std::string notFound = std::string(kind) + " file not found: " + written.string();
  if (written.is_absolute()) return notFound;
  return notFound + " (looked in " + sceneDir.string() + " and " + sceneDir.parent_path().string() +
         ")";
}

void readTextureFile(const JsonNode& node, const fs::path& sceneDir, Material& out, Scene& scene) {
  bool found = false;
  try {
    found = useDiffuseTextureFile(scene, out, findReferencedFile(node, sceneDir));
  } catch (const Error& error) {
    node.fail(error.what());
  }
  if (found) return;
  node.warn(notFoundMessage(node, sceneDir, "texture") +
            "; drawn with the missing-texture squares");
  out.texture = node.string();
}

}  // namespace rt
