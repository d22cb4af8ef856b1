// The run folder's lock (harness/run/folder_lock.hpp): a second holder is refused with one line
// naming the first (flock conflicts between open file descriptions, so within one process too);
// release removes the file; a lock file left by a dead holder is taken over.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "harness/run/folder_lock.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using dabench::test::cli::read_text;
using dabench::test::cli::TempDir;
using dabench::test::cli::write_text;

TEST_CASE("a locked folder refuses a second lock, naming its holder, until released") {
  const TempDir dir;
  const std::string folder = (dir.work() / "run").string();
  const auto lock_file = dir.work() / "run" / ".dabench.lock";
  {
    FolderLock held(folder, "run");  // creates the folder
    CHECK(std::filesystem::is_directory(folder));
    CHECK_THAT(read_text(lock_file), Catch::StartsWith(fmt::format("pid {} on ", getpid())));
    const std::string message = test::input_error_message([&] { FolderLock second(folder, "merge"); });
    CHECK_THAT(message, Catch::StartsWith(fmt::format("{}: in use by dabench pid {} on ", folder, getpid())));
    CHECK_THAT(message, Catch::EndsWith("Z (run); wait for it to end or stop it"));
    held.release();
    CHECK_FALSE(std::filesystem::exists(lock_file));
    FolderLock again(folder, "merge");
    CHECK_THAT(read_text(lock_file), Catch::EndsWith("(merge)\n"));
  }
  CHECK_FALSE(std::filesystem::exists(lock_file));
}

TEST_CASE("a lock file whose holder is gone is taken over") {
  const TempDir dir;
  write_text(dir.work() / "run" / ".dabench.lock", "pid 1 on elsewhere since 2026-01-01T00:00:00Z (run)\n");
  FolderLock taken((dir.work() / "run").string(), "run");
  CHECK_THAT(read_text(dir.work() / "run" / ".dabench.lock"), Catch::StartsWith(fmt::format("pid {} on ", getpid())));
}

}  // namespace DABENCH_TEST_FILE
