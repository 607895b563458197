// Watches folders with inotify for files that were written or renamed into
// place (editors save either way), without blocking. Folders rather than the
// files themselves are watched so that a save by rename keeps being seen.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <vector>

namespace rt::viewer {

class FileWatcher {
 public:
  FileWatcher();
  ~FileWatcher();
  FileWatcher(const FileWatcher&) = delete;
  FileWatcher& operator=(const FileWatcher&) = delete;

  // Throws rt::Error when the folder cannot be watched.
  void watchFolder(const std::filesystem::path& folder);

  // Files written since the last call (full paths, possibly repeated).
  std::vector<std::filesystem::path> poll();

 private:
  int fd_ = -1;
  std::map<int, std::filesystem::path> folders_;  // watch descriptor -> folder
};

// Collects changes until none came for a short while, so an editor's save in
// several steps (truncate, write, rename) triggers one reload.
class Debouncer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit Debouncer(std::chrono::milliseconds quiet) : quiet_(quiet) {}

  void notify(Clock::time_point when);
  // True once, when changes came and then none for `quiet`.
  bool ready(Clock::time_point now);
  // When the first change of the batch that became ready was seen.
  Clock::time_point firstChange() const { return first_; }

 private:
  std::chrono::milliseconds quiet_;
  bool pending_ = false;
  Clock::time_point first_{};
  Clock::time_point last_{};
};

}  // namespace rt::viewer
