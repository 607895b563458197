#include "io/AtomicFile.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "util/Error.hpp"

namespace rt {
namespace {

std::filesystem::path temporaryPathFor(const std::filesystem::path& target) {
  std::filesystem::path tmp = target;
  tmp += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  return tmp;
}

void writeAll(int fd, const void* data, size_t bytes, const std::filesystem::path& path) {
  const char* cursor = static_cast<const char*>(data);
  while (bytes > 0) {
    ssize_t written = ::write(fd, cursor, bytes);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0)
      throw Error(fmt::format("{}: write failed: {}", path.string(), std::strerror(errno)));
    cursor += written;
    bytes -= static_cast<size_t>(written);
  }
}

}  // namespace

void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path&)>& writeTo) {
  std::filesystem::path tmp = temporaryPathFor(target);
  try {
    writeTo(tmp);
    std::error_code error;
    std::filesystem::rename(tmp, target, error);
    if (error) throw Error(fmt::format("{}: cannot write: {}", target.string(), error.message()));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

void checkWritable(const std::filesystem::path& target) {
  std::filesystem::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ignored;
  if (std::filesystem::is_directory(target, ignored))
    throw Error(fmt::format("{}: cannot write: it is a folder", target.string()));
  if (!std::filesystem::is_directory(folder, ignored)) {
    throw Error(fmt::format("{}: cannot write: no folder {}", target.string(), folder.string()));
  }
  if (::access(folder.c_str(), W_OK) != 0)
    throw Error(fmt::format("{}: cannot write: {}", target.string(), std::strerror(errno)));
}

void writeFileAtomically(const std::filesystem::path& target, const void* data, size_t bytes) {
  writeAtomically(target, [&](const std::filesystem::path& tmp) {
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      throw Error(fmt::format("{}: cannot write: {}", target.string(), std::strerror(errno)));
    try {
      writeAll(fd, data, bytes, target);
      if (::fsync(fd) != 0)
        throw Error(fmt::format("{}: fsync failed: {}", target.string(), std::strerror(errno)));
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0)
      throw Error(fmt::format("{}: close failed: {}", target.string(), std::strerror(errno)));
  });
}

}  // namespace rt
