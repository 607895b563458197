#include "util/Text.hpp"

#include <algorithm>
#include <cctype>

namespace rt {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string lowerExtension(const std::filesystem::path& file) {
  return lowercase(file.extension().string());
}

bool hasExtension(const std::filesystem::path& file,
                  std::initializer_list<std::string_view> extensions) {
  const std::string ext = lowerExtension(file);
  return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
}

}  // namespace rt
