#include "harness/run/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/run/run_meta.hpp"

namespace dabench {

namespace {

// The holder's line ("pid 123 on host since 2026-01-31T12:00:00Z (run)"), waited for up to
// 0.2 s when the holder has locked the file but not written it yet.
std::string holder_of(int fd) {
  for (int attempt = 0; attempt < 40; ++attempt) {
    char text[512] = {};
    const ssize_t read = pread(fd, text, sizeof(text) - 1, 0);
    std::string line = read > 0 ? std::string(text, static_cast<std::size_t>(read)) : std::string();
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      return "dabench " + line;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return "another dabench process (starting)";
}

bool same_file(int fd, const std::string& path) {
  struct stat opened {}, named {};
  return fstat(fd, &opened) == 0 && stat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
         opened.st_ino == named.st_ino;
}

}  // namespace

FolderLock::FolderLock(const std::string& folder, const std::string& command) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw InputError(fmt::format("{}: cannot create output folder ({})", folder, error.message()));
  path_ = (std::filesystem::path(folder) / ".dabench.lock").string();
  // A releasing holder unlinks the file it locked: a lock on that unlinked file locks nothing,
  // so the file locked must still be the one the path names.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) throw WriteError(fmt::format("{}: cannot create the folder's lock file ({})", path_, std::strerror(errno)));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int reason = errno;
      const std::string holder = reason == EWOULDBLOCK ? holder_of(fd) : "";
      close(fd);
      if (reason == EWOULDBLOCK) {
        throw InputError(fmt::format("{}: in use by {}; wait for it to end or stop it", folder, holder));
      }
      throw InputError(fmt::format("{}: cannot lock the folder ({})", folder, std::strerror(reason)));
    }
    if (!same_file(fd, path_)) {
      close(fd);
      continue;
    }
    const std::string line = fmt::format("pid {} on {} since {} ({})\n", getpid(), host_name(), utc_now(), command);
    if (ftruncate(fd, 0) != 0 || pwrite(fd, line.data(), line.size(), 0) != static_cast<ssize_t>(line.size())) {
      const int reason = errno;
      unlink(path_.c_str());
      close(fd);
      throw WriteError(fmt::format("{}: write failed ({})", path_, std::strerror(reason)));
    }
    fd_ = fd;
    return;
  }
  throw InputError(fmt::format("{}: cannot lock the folder (its lock file keeps being replaced)", folder));
}

void FolderLock::release() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // while still locked: the next process then creates a fresh file
  close(fd_);
  fd_ = -1;
}

FolderLock::~FolderLock() { release(); }

}  // namespace dabench
