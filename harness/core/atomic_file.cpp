#include "harness/core/atomic_file.hpp"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

void write_file_atomically(const std::string& path, const std::string& contents) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr) throw InputError(fmt::format("{}: cannot write", path));
  const bool written = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  const bool closed = std::fclose(file) == 0;
  std::error_code error;
  if (!written || !closed) {
    std::filesystem::remove(temporary, error);
    throw InputError(fmt::format("{}: write failed (disk full?)", path));
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw InputError(fmt::format("{}: cannot replace file", path));
  }
}

}  // namespace dabench
