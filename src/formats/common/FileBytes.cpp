#include "formats/common/FileBytes.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "util/Error.hpp"

namespace rt {
namespace {

namespace fs = std::filesystem;

template <typename Bytes>
std::string readInto(const fs::path& file, Bytes& bytes) {
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (error) return "cannot open: " + error.message();
  if (fs::is_directory(status)) return std::string("cannot open: ") + std::strerror(EISDIR);
  if (!fs::is_regular_file(status)) return "cannot open: not a regular file";
  const uint64_t size = fs::file_size(file, error);
  if (error) return "cannot open: " + error.message();
  if (size > kMaxInputFileBytes) {
    return "file is " + std::to_string(size >> 20) + " MiB, more than the " +
           std::to_string(kMaxInputFileBytes >> 20) + " MiB allowed";
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::string("cannot open: ") + std::strerror(errno);
  bytes.resize(size_t(size));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
  if (uint64_t(in.gcount()) != size) return "cannot read the whole file";
  return {};
}

}  // namespace

std::string readFileBytes(const fs::path& file, std::string& bytes) {
  return readInto(file, bytes);
}

std::string readFileBytes(const fs::path& file, std::vector<unsigned char>& bytes) {
  return readInto(file, bytes);
}

std::string readFileOrThrow(const fs::path& file) {
  std::string bytes;
  if (std::string problem = readFileBytes(file, bytes); !problem.empty()) {
    throw Error(file.string() + ": " + problem);
  }
  return bytes;
}

fs::path portablePath(std::string written) {
  std::replace(written.begin(), written.end(), '\\', '/');
  return fs::path(written);
}

}  // namespace rt
