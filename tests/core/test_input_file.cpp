// Input files and quoted text (harness/core/input_file.hpp): only regular files of bounded size
// are read, and printable() escapes exactly the bytes a terminal must not see.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "tests/support/cli_runner.hpp"

namespace DABENCH_TEST_FILE {

using dabench::InputError;
using dabench::printable;

TEST_CASE("input file: regular files of bounded size only", "[input]") {
  dabench::test::cli::TempDir dir;
  dir.write("small.ini", "trials = 1\n");
  CHECK(dabench::read_input_file((dir.work() / "small.ini").string(), "an experiment file", 64) == "trials = 1\n");
  CHECK_THROWS_WITH(dabench::read_input_file((dir.work() / "small.ini").string(), "an experiment file", 10),
                    Catch::Contains("11 bytes") && Catch::Contains("at most 10 bytes"));
  CHECK_THROWS_WITH(dabench::read_input_file((dir.work() / "none.ini").string(), "an experiment file", 64),
                    Catch::Contains("no such file"));
  std::filesystem::create_directories(dir.work() / "folder");
  CHECK_THROWS_WITH(dabench::read_input_file((dir.work() / "folder").string(), "an experiment file", 64),
                    Catch::Contains("is a folder"));
  for (const char* device : {"/dev/zero", "/dev/null", "/dev/full"}) {
    CHECK_THROWS_WITH(dabench::check_input_file(device, "a weights file", 64), Catch::Contains("not a regular file"));
  }
}

TEST_CASE("input file: printable escapes control bytes and malformed UTF-8 only", "[input]") {
  CHECK(printable("plain text: a = 1, [scenario]") == "plain text: a = 1, [scenario]");
  CHECK(printable("γ = 0.95, café") == "γ = 0.95, café");                      // 2-byte UTF-8 kept
  CHECK(printable("\xE2\x88\x9E and \xF0\x9F\x98\x80") == "\xE2\x88\x9E and \xF0\x9F\x98\x80");  // 3, 4 bytes
  CHECK(printable(std::string("a\0b", 3)) == "a\\x00b");
  CHECK(printable("\x1b[2J\r\n\t\x7f") == "\\x1B[2J\\x0D\\x0A\\x09\\x7F");
  CHECK(printable("\xff\xfe") == "\\xFF\\xFE");                                // never UTF-8
  CHECK(printable("\xC0\xAF") == "\\xC0\\xAF");                                // overlong '/'
  CHECK(printable("\xED\xA0\x80") == "\\xED\\xA0\\x80");                       // a surrogate
  CHECK(printable("\xF4\x90\x80\x80") == "\\xF4\\x90\\x80\\x80");              // beyond U+10FFFF
  CHECK(printable("\xE2\x88") == "\\xE2\\x88");                                // cut short at the end
  CHECK(printable("\xC3") == "\\xC3");
}

}  // namespace DABENCH_TEST_FILE
