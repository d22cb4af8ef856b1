#include "harness/core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

void write_file_atomically(const std::string& path, const std::string& contents) {
  // Named per process: two processes writing one file never share (or remove) a temporary.
  const std::string temporary = fmt::format("{}.tmp.{}", path, getpid());
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr) throw WriteError(fmt::format("{}: cannot write ({})", path, std::strerror(errno)));
  const bool written = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  int reason = written ? 0 : errno;
  const bool closed = std::fclose(file) == 0;  // a buffered write may fail only here
  if (written && !closed) reason = errno;
  std::error_code error;
  if (!written || !closed) {
    std::filesystem::remove(temporary, error);
    throw WriteError(fmt::format("{}: write failed ({})", path, std::strerror(reason)));
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    const std::string message = error.message();
    std::filesystem::remove(temporary, error);
    throw WriteError(fmt::format("{}: cannot replace file ({})", path, message));
  }
}

}  // namespace dabench
