#include "formats/common/Diagnostics.hpp"

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
  std::string line = format(where, what);
  if (seen_.insert(line).second) warnings_.push_back(std::move(line));
}

std::vector<std::string> Diagnostics::takeWarnings() {
  seen_.clear();
  return std::move(warnings_);
}

std::string byteOffset(size_t offset) { return "byte " + std::to_string(offset); }

}  // namespace rt
