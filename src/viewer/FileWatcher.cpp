#include "viewer/FileWatcher.hpp"

#include <fmt/format.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "util/Error.hpp"

namespace rt::viewer {

FileWatcher::FileWatcher() {
  fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd_ < 0) throw Error(fmt::format("inotify_init1 failed: {}", std::strerror(errno)));
}

FileWatcher::~FileWatcher() {
  if (fd_ >= 0) close(fd_);
}

void FileWatcher::watchFolder(const std::filesystem::path& folder) {
  // Written and closed (in-place saves, cp) or renamed into the folder
  // (editors that write a temporary file first, sed -i).
  int wd = inotify_add_watch(fd_, folder.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO);
  if (wd < 0) {
    throw Error(
        fmt::format("{}: cannot watch for changes: {}", folder.string(), std::strerror(errno)));
  }
  folders_[wd] = folder;
}

std::vector<std::filesystem::path> FileWatcher::poll() {
  std::vector<std::filesystem::path> changed;
  alignas(inotify_event) char buffer[16384];
  for (;;) {
    ssize_t bytes = read(fd_, buffer, sizeof(buffer));
    if (bytes <= 0) break;  // EAGAIN: nothing more to read
    for (ssize_t offset = 0; offset < bytes;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + offset);
      auto folder = folders_.find(event->wd);
      if (folder != folders_.end() && event->len > 0) {
        changed.push_back(folder->second / event->name);
      }
      offset += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
    }
  }
  return changed;
}

void Debouncer::notify(Clock::time_point when) {
  if (!pending_) first_ = when;
  pending_ = true;
  last_ = when;
}

bool Debouncer::ready(Clock::time_point now) {
  if (!pending_ || now - last_ < quiet_) return false;
  pending_ = false;
  return true;
}

}  // namespace rt::viewer
