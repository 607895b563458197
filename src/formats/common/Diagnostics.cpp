#include "formats/common/Diagnostics.hpp"

#include <algorithm>

#include "util/Error.hpp"

namespace rt {

std::string Diagnostics::format(std::string_view where, std::string_view what) const {
  std::string line = file_;
  line += ": ";
  if (!where.empty()) {
    line += where;
    line += ": ";
  }
  line += what;
  return line;
}

void Diagnostics::fail(std::string_view where, std::string_view what) const {
  throw Error(format(where, what));
}

void Diagnostics::failAtByte(size_t offset, std::string_view what) const {
  fail(byteOffset(offset), what);
}

void Diagnostics::warn(std::string_view where, std::string_view what) {
  auto [entry, added] = byWhat_.try_emplace(std::string(what), warnings_.size());
  if (added) warnings_.push_back({std::string(what), {}, {}});
  Warning& warning = warnings_[entry->second];
  if (warning.seen.emplace(where).second) warning.places.emplace_back(where);
}

std::vector<std::string> Diagnostics::takeWarnings() {
  // A line names at most this many places, then how many more there are.
  constexpr size_t kPlacesNamed = 3;
  std::vector<std::string> lines;
  for (const Warning& warning : warnings_) {
    std::string places;
    for (size_t i = 0; i < std::min(warning.places.size(), kPlacesNamed); ++i) {
      if (warning.places[i].empty()) continue;
      if (!places.empty()) places += ", ";
      places += warning.places[i];
    }
    if (warning.places.size() > kPlacesNamed) {
      places += " and " + std::to_string(warning.places.size() - kPlacesNamed) + " more";
    }
    lines.push_back(format(places, warning.what));
  }
  warnings_.clear();
  byWhat_.clear();
  return lines;
}

void Diagnostics::noteRead(std::string_view where, std::string_view value) {
  std::string line(where);
  line += " = ";
  line += value;
  reads_.push_back(std::move(line));
}

std::string byteOffset(size_t offset) { return "byte " + std::to_string(offset); }

}  // namespace rt
