// checksums.csv (harness/run/row_checksums.hpp): FNV-1a values, the lines the runner appends,
// reading them back per file (a last line cut short ignored, a malformed one an error), and the
// verification that names the first row edited, cut short or deleted.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/run/row_checksums.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using dabench::test::cli::read_text;
using dabench::test::cli::TempDir;
using dabench::test::cli::write_text;

const std::string kHeader = "point,trial,value\n";
const std::string kRows = "0,0,1.5\n0,1,2.5\n1,0,3.5\n";

// A folder with trials.csv (kHeader + rows) and the checksums.csv the runner would write for it
// in blocks, interleaved with lines of another file.
void write_run(const TempDir& dir, const std::string& rows) {
  write_text(dir.work() / "trials.csv", kHeader + rows);
  std::string lines = kChecksumsHeader;
  append_checksum_lines(lines, {"targets.csv", "trials.csv"}, {"0,0,x\n", rows.substr(0, 16)});
  append_checksum_lines(lines, {"targets.csv", "trials.csv"}, {"", rows.substr(16)});
  write_text(dir.work() / kChecksumsFile, lines);
}

std::vector<long long> verified_lines(const TempDir& dir) {
  RecordedChecksums recorded((dir.work() / kChecksumsFile).string(), "trials.csv");
  std::vector<long long> lines;
  verify_rows((dir.work() / "trials.csv").string(), kHeader.size(), recorded,
              [&](long long row, std::string_view, std::uintmax_t) { lines.push_back(row + 2); });
  return lines;
}

TEST_CASE("row checksums are 32-bit FNV-1a of the row without its newline") {
  CHECK(row_checksum("") == 0x811c9dc5u);
  CHECK(row_checksum("a") == 0xe40c292cu);
  CHECK(row_checksum("foobar") == 0xbf9cf968u);
  std::string lines;
  append_checksum_lines(lines, {"a.csv", "b.csv"}, {"a\n", "\nfoobar\n"});
  CHECK(lines == "a.csv,e40c292c\nb.csv,811c9dc5 bf9cf968\n");
}

TEST_CASE("verify_rows accepts the rows written and names the first one changed") {
  const TempDir dir;
  write_run(dir, kRows);
  CHECK(verified_lines(dir) == std::vector<long long>{2, 3, 4});

  SECTION("a value edited") {
    write_text(dir.work() / "trials.csv", kHeader + "0,0,1.5\n0,1,2.6\n1,0,3.5\n");
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("trials.csv:3: not the row written there"));
  }
  SECTION("a row cut short, its newline kept") {
    write_text(dir.work() / "trials.csv", kHeader + "0,0,1.5\n0,1,2.5\n1,0,3\n");
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("trials.csv:4: not the row written there"));
  }
  SECTION("a row deleted") {
    write_text(dir.work() / "trials.csv", kHeader + "0,0,1.5\n1,0,3.5\n");
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("trials.csv:3: not the row written there"));
  }
  SECTION("the last rows deleted") {
    write_text(dir.work() / "trials.csv", kHeader + "0,0,1.5\n0,1,2.5\n");
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("trials.csv:4: missing: checksums.csv records more rows"));
  }
  SECTION("rows after the recorded ones (written just before a kill) are left unverified") {
    write_text(dir.work() / "trials.csv", kHeader + kRows + "1,1,4.5\n1,2,5");
    CHECK(verified_lines(dir) == std::vector<long long>{2, 3, 4});
  }
  SECTION("a last checksums line cut short records nothing") {
    const std::string lines = read_text(dir.work() / kChecksumsFile);
    write_text(dir.work() / kChecksumsFile, lines.substr(0, lines.size() - 4));
    CHECK(verified_lines(dir) == std::vector<long long>{2, 3});
  }
  SECTION("a malformed checksums line is an error naming it") {
    write_text(dir.work() / kChecksumsFile, std::string(kChecksumsHeader) + "trials.csv,12345\n");
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("checksums.csv:2: malformed checksum '12345'"));
  }
  SECTION("no checksums.csv") {
    std::filesystem::remove(dir.work() / kChecksumsFile);
    CHECK_THAT(test::input_error_message([&] { verified_lines(dir); }), Catch::Contains("checksums.csv: missing or not a dabench checksums file"));
  }
}

TEST_CASE("rewrite_checksums records the first rows of each file, as the runner wrote them") {
  const TempDir dir;
  write_run(dir, kRows);
  write_text(dir.work() / "targets.csv", "point,trial,target\n0,0,x\n");
  rewrite_checksums(dir.work().string(), {"targets.csv", "trials.csv"}, {19, kHeader.size()}, {1, 2});
  CHECK(read_text(dir.work() / kChecksumsFile) ==
        std::string(kChecksumsHeader) + "targets.csv," + fmt::format("{:08x}", row_checksum("0,0,x")) + "\ntrials.csv," +
            fmt::format("{:08x} {:08x}", row_checksum("0,0,1.5"), row_checksum("0,1,2.5")) + "\n");
  CHECK(verified_lines(dir) == std::vector<long long>{2, 3});
}

}  // namespace DABENCH_TEST_FILE
