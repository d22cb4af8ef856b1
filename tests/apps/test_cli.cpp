// The command-line contract of DESIGN.md ("Command line"), tested on the real executable:
//  - every error path exits with status != 0, prints exactly one line on stderr naming the
//    problem (and the file/line where there is one), prints nothing on stdout, and leaves no
//    file behind (the working folder is byte-identical before and after);
//  - `solve` prints target,measurement,probability with n·(m+1) rows, 1-based targets,
//    measurement 0 = missed detection, rows summing to 1, and the closed-form marginals of a
//    hand-computable 2×2 problem (also in --format json); `solve --time` prints one parseable
//    row (or JSON object) with a positive median inside its percentiles and the repetition count;
//  - `run` rejects every bad experiment before creating its output folder, refuses a folder
//    that holds a run unless --resume/--force (and then leaves it untouched), and refuses to
//    resume a different run;
//  - `list` names the algorithms, the scenarios and the experiment files;
//  - `run --shard K/N` and `merge`: merged shards equal the run; missing, duplicated, foreign,
//    incomplete shards and bad K/N are one-line errors that leave no file;
//  - `--version` and every command's `--help`/`-h` print on stdout and exit 0.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "harness/core/build_info.hpp"
#include "tests/support/cli_runner.hpp"

using namespace dabench::test::cli;

namespace {

int count_newlines(const std::string& text) {
  int count = 0;
  for (const char c : text) count += c == '\n';
  return count;
}

// Runs dabench with `args` in dir.work(); requires the error contract and that every string of
// `mentions` occurs in the message. Returns the stderr line.
std::string expect_error(const TempDir& dir, const std::vector<std::string>& args,
                         const std::vector<std::string>& mentions) {
  const auto before = snapshot(dir.work());
  const CliResult result = run_dabench(dir, args);
  std::string shown;
  for (const auto& arg : args) shown += " " + arg;
  INFO("dabench" << shown);
  INFO("stderr: " << result.err);
  CHECK_FALSE(result.signaled);
  CHECK(result.status != 0);
  CHECK(result.out.empty());
  CHECK(count_newlines(result.err) == 1);
  CHECK((!result.err.empty() && result.err.back() == '\n'));
  for (const auto& part : mentions) {
    INFO("the message should mention: " << part);
    CHECK(contains(result.err, part));
  }
  CHECK(snapshot(dir.work()) == before);
  return result.err;
}

CliResult run_ok(const TempDir& dir, const std::vector<std::string>& args) {
  const CliResult result = run_dabench(dir, args);
  INFO("stderr: " << result.err);
  REQUIRE(result.status == 0);
  return result;
}

struct MarginalRow {
  int target = 0;
  int measurement = 0;
  double probability = 0.0;
};

// Parses solve's CSV output and checks its shape: header, n·(m+1) rows in (target, measurement)
// order, probabilities in [0, 1], each target's row summing to 1.
std::vector<MarginalRow> check_solve_csv(const std::string& out, int n, int m) {
  const auto lines = split_lines(out);
  REQUIRE(!lines.empty());
  CHECK(lines[0] == "target,measurement,probability");
  REQUIRE(lines.size() == static_cast<std::size_t>(1 + n * (m + 1)));
  CHECK(out.back() == '\n');
  std::vector<MarginalRow> rows;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto fields = parse_csv_line(lines[k]);
    REQUIRE(fields.size() == 3);
    MarginalRow row{std::stoi(fields[0]), std::stoi(fields[1]), to_double(fields[2])};
    const int index = static_cast<int>(k - 1);
    CHECK(row.target == index / (m + 1) + 1);
    CHECK(row.measurement == index % (m + 1));
    CHECK(row.probability >= 0.0);
    CHECK(row.probability <= 1.0);
    rows.push_back(row);
  }
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j <= m; ++j) sum += rows[static_cast<std::size_t>(i * (m + 1) + j)].probability;
    INFO("target " << i + 1);
    CHECK(sum == Approx(1.0).margin(1e-12));
  }
  return rows;
}

// A strict JSON syntax check (RFC 8259 grammar, no extensions), enough to say "it parses".
class JsonChecker {
 public:
  explicit JsonChecker(const std::string& text) : text_(text) {}
  bool valid() {
    at_ = 0;
    if (!value()) return false;
    space();
    return at_ == text_.size();
  }

 private:
  void space() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (text_.compare(at_, w.size(), w) != 0) return false;
    at_ += w.size();
    return true;
  }
  bool string() {
    if (text_[at_] != '"') return false;
    for (++at_; at_ < text_.size(); ++at_) {
      const char c = text_[at_];
      if (c == '"') {
        ++at_;
        return true;
      }
      if (static_cast<unsigned char>(c) < 0x20) return false;
      if (c == '\\') ++at_;
    }
    return false;
  }
  bool number() {
    const char* begin = text_.c_str() + at_;
    if (*begin != '-' && !std::isdigit(static_cast<unsigned char>(*begin))) return false;
    char* end = nullptr;
    std::strtod(begin, &end);
    if (end == begin) return false;
    const std::string token(begin, static_cast<const char*>(end));
    if (token.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;  // no nan/inf/hex
    at_ += static_cast<std::size_t>(end - begin);
    return true;
  }
  bool value() {
    space();
    if (at_ >= text_.size()) return false;
    const char c = text_[at_];
    if (c == '{') return container('}', true);
    if (c == '[') return container(']', false);
    if (c == '"') return string();
    if (c == 't') return literal("true");
    if (c == 'f') return literal("false");
    if (c == 'n') return literal("null");
    return number();
  }
  bool container(char close, bool object) {
    ++at_;
    space();
    if (at_ < text_.size() && text_[at_] == close) {
      ++at_;
      return true;
    }
    while (true) {
      space();
      if (object) {
        if (at_ >= text_.size() || !string()) return false;
        space();
        if (at_ >= text_.size() || text_[at_++] != ':') return false;
      }
      if (!value()) return false;
      space();
      if (at_ >= text_.size()) return false;
      const char next = text_[at_++];
      if (next == close) return true;
      if (next != ',') return false;
    }
  }

  const std::string& text_;
  std::size_t at_ = 0;
};

// The numbers of the JSON array that follows "key": (flattened, in order).
std::vector<double> json_numbers_after(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  REQUIRE(at != std::string::npos);
  const auto open = json.find('[', at);
  REQUIRE(open != std::string::npos);
  std::vector<double> numbers;
  int depth = 0;
  for (std::size_t k = open; k < json.size(); ++k) {
    const char c = json[k];
    if (c == '[') {
      ++depth;
    } else if (c == ']') {
      if (--depth == 0) break;
    } else if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) {
      char* end = nullptr;
      numbers.push_back(std::strtod(json.c_str() + k, &end));
      k = static_cast<std::size_t>(end - json.c_str()) - 1;
    }
  }
  return numbers;
}

// ψ = [[a, b], [c, d]]: the events are {none, 1→1, 1→2, 2→1, 2→2, 1→1&2→2, 1→2&2→1}, so
// Z = 1 + a + b + c + d + ad + bc and
//   p(a1=0) = (1+c+d)/Z, p(a1=1) = a(1+d)/Z, p(a1=2) = b(1+c)/Z,
//   p(a2=0) = (1+a+b)/Z, p(a2=1) = c(1+b)/Z, p(a2=2) = d(1+a)/Z.
constexpr double kA = 0.5, kB = 2.0, kC = 3.0, kD = 0.25;
const char* const kWeights2x2 = "0.5,2\n3,0.25\n";
std::vector<double> marginals_2x2() {
  const double z = 1 + kA + kB + kC + kD + kA * kD + kB * kC;
  return {(1 + kC + kD) / z, kA * (1 + kD) / z, kB * (1 + kC) / z,
          (1 + kA + kB) / z, kC * (1 + kB) / z, kD * (1 + kA) / z};
}

const char* const kGoodExperiment =
    "scenario = grid\n"
    "trials = 3\n"
    "seed = 5\n"
    "output = out\n"
    "reference = exact\n"
    "algorithm = bp\n"
    "[scenario]\n"
    "rows = 1\n"
    "cols = 2\n"
    "[sweep]\n"
    "spacing = 1, 2\n";

// kGoodExperiment with `line` inserted after the top-level keys (before [scenario]) or appended.
std::string experiment_with(const std::string& top, const std::string& tail = "") {
  std::string text = kGoodExperiment;
  text.insert(text.find("[scenario]"), top);
  return text + tail;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// solve: errors

TEST_CASE("cli solve: malformed weights files are rejected naming file and line", "[cli][solve]") {
  TempDir dir;
  dir.write("ok.csv", kWeights2x2);
  SECTION("ragged rows") {
    dir.write("ragged.csv", "1,2\n3,4\n5\n");
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "ragged.csv"}, {"ragged.csv:3", "ragged"});
  }
  SECTION("non-numeric field") {
    dir.write("text.csv", "1,2\n3,abc\n");
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "text.csv"}, {"text.csv:2", "abc"});
  }
  SECTION("negative weight") {
    dir.write("negative.csv", "1,-0.5\n");
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "negative.csv"}, {"negative.csv:1", "negative"});
  }
  SECTION("nan") {
    dir.write("nan.csv", "1,2\nnan,1\n");
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "nan.csv"}, {"nan.csv:2", "nan"});
  }
  SECTION("inf") {
    dir.write("inf.csv", "inf,1\n");
    expect_error(dir, {"solve", "--algorithm", "exact", "--weights", "inf.csv"}, {"inf.csv:1", "inf"});
  }
  SECTION("empty file") {
    dir.write("empty.csv", "");
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "empty.csv"}, {"empty.csv", "empty"});
  }
  SECTION("missing file") {
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "missing.csv"}, {"missing.csv"});
  }
  SECTION("a character device is refused at once, not read forever") {
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "/dev/zero"}, {"/dev/zero", "not a regular file"});
  }
  SECTION("binary content is quoted escaped") {
    dir.write("binary.csv", std::string("1,2\n3,\x1b[2J\x01\xff\n", 13));
    const std::string err = expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "binary.csv"}, {"binary.csv:2"});
    CHECK(contains(err, "\\x1B[2J\\x01\\xFF"));
    CHECK(std::none_of(err.begin(), err.end() - 1, [](char c) { return static_cast<unsigned char>(c) < 0x20; }));
  }
}

TEST_CASE("cli solve: bad algorithm specs and options are rejected", "[cli][solve]") {
  TempDir dir;
  dir.write("ok.csv", kWeights2x2);
  SECTION("unknown algorithm") {
    expect_error(dir, {"solve", "--algorithm", "nosuch", "--weights", "ok.csv"}, {"nosuch"});
  }
  SECTION("unknown parameter") {
    expect_error(dir, {"solve", "--algorithm", "bp:foo=1", "--weights", "ok.csv"}, {"foo"});
  }
  SECTION("malformed value") {
    expect_error(dir, {"solve", "--algorithm", "bp:delta=abc", "--weights", "ok.csv"}, {"delta", "abc"});
  }
  SECTION("out-of-range value") {
    expect_error(dir, {"solve", "--algorithm", "bp:check_every=0", "--weights", "ok.csv"}, {"check_every"});
  }
  SECTION("missing --weights") {
    expect_error(dir, {"solve", "--algorithm", "bp"}, {"weights"});
  }
  SECTION("missing --algorithm") {
    expect_error(dir, {"solve", "--weights", "ok.csv"}, {"algorithm"});
  }
  SECTION("bad --format") {
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "ok.csv", "--format", "xml"}, {"format", "xml"});
  }
  SECTION("--pd outside (0, 1)") {
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "ok.csv", "--pd", "1.5"}, {"pd", "1.5"});
  }
  SECTION("unknown option") {
    expect_error(dir, {"solve", "--algorithm", "bp", "--weights", "ok.csv", "--bogus"}, {"bogus"});
  }
}

TEST_CASE("cli solve: exact past its work limit exits 3 with a skipped line", "[cli][solve]") {
  TempDir dir;
  std::string ones;
  for (int i = 0; i < 6; ++i) ones += "1,1,1,1,1,1\n";
  dir.write("dense.csv", ones);
  const auto before = snapshot(dir.work());
  const CliResult result = run_dabench(dir, {"solve", "--algorithm", "exact:max_events=10", "--weights", "dense.csv"});
  INFO("stderr: " << result.err);
  CHECK(result.status == 3);
  CHECK(result.out.empty());
  CHECK(count_newlines(result.err) == 1);
  CHECK(contains(result.err, "skipped:"));
  CHECK(snapshot(dir.work()) == before);
}

// ---------------------------------------------------------------------------------------------
// solve: output

TEST_CASE("cli solve: exact matches the hand-computed 2x2 marginals", "[cli][solve]") {
  TempDir dir;
  dir.write("w.csv", kWeights2x2);
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "exact", "--weights", "w.csv"});
  CHECK(result.err.empty());
  const auto rows = check_solve_csv(result.out, 2, 2);
  const auto expected = marginals_2x2();
  for (std::size_t k = 0; k < expected.size(); ++k) {
    INFO("row " << k + 1);
    CHECK(rows[k].probability == Approx(expected[k]).epsilon(1e-13));
  }
}

TEST_CASE("cli solve: output shape for bp and exact on a 3x4 problem", "[cli][solve]") {
  TempDir dir;
  // Row 2 gates nothing (all zero): p(a2 = 0) = 1. Trailing blank lines and spaces are allowed.
  dir.write("w.csv", "0.5, 1, 0, 2\n0,0,0,0\n3,0.25,1.5,0\n\n");
  for (const std::string spec : {"bp", "exact", "bp:delta=1e-9,check_every=1"}) {
    INFO("spec " << spec);
    const CliResult result = run_ok(dir, {"solve", "--algorithm", spec, "--weights", "w.csv"});
    const auto rows = check_solve_csv(result.out, 3, 4);
    CHECK(rows[5].probability == 1.0);  // target 2, measurement 0
    for (int j = 1; j <= 4; ++j) CHECK(rows[static_cast<std::size_t>(5 + j)].probability == 0.0);
    CHECK(rows[3].probability == 0.0);  // ψ_1(3) = 0 is impossible
  }
}

TEST_CASE("cli solve: bp is exact on a single target", "[cli][solve]") {
  // One target: no loops, p(a=j) = ψ_j / (1 + Σψ) with ψ_0 = 1.
  TempDir dir;
  dir.write("w.csv", "0.5,2,1.5\n");
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "bp", "--weights", "w.csv"});
  const auto rows = check_solve_csv(result.out, 1, 3);
  const double z = 1 + 0.5 + 2 + 1.5;
  const double expected[] = {1 / z, 0.5 / z, 2 / z, 1.5 / z};
  for (int j = 0; j <= 3; ++j) CHECK(rows[static_cast<std::size_t>(j)].probability == Approx(expected[j]).epsilon(1e-12));
}

TEST_CASE("cli solve: --format json parses and holds the marginals", "[cli][solve]") {
  TempDir dir;
  dir.write("w.csv", kWeights2x2);
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "exact", "--weights", "w.csv", "--format", "json"});
  INFO("stdout: " << result.out);
  CHECK(JsonChecker(result.out).valid());
  CHECK(contains(result.out, "\"algorithm\": \"exact\""));
  CHECK(contains(result.out, "\"targets\": 2"));
  CHECK(contains(result.out, "\"measurements\": 2"));
  const auto numbers = json_numbers_after(result.out, "marginals");
  const auto expected = marginals_2x2();
  REQUIRE(numbers.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) CHECK(numbers[k] == Approx(expected[k]).epsilon(1e-13));

  // The same numbers as the CSV output, and a SPEC with a comma survives JSON quoting.
  const CliResult csv = run_ok(dir, {"solve", "--algorithm", "exact", "--weights", "w.csv"});
  const auto rows = check_solve_csv(csv.out, 2, 2);
  for (std::size_t k = 0; k < expected.size(); ++k) CHECK(numbers[k] == rows[k].probability);
  const CliResult bp = run_ok(dir, {"solve", "--algorithm", "bp:delta=1e-6,check_every=10", "--weights", "w.csv",
                                    "--format", "json"});
  CHECK(JsonChecker(bp.out).valid());
  CHECK(contains(bp.out, "\"algorithm\": \"bp:delta=1e-6,check_every=10\""));
}

TEST_CASE("cli solve: --format json reports fbp's free energy", "[cli][solve]") {
  // One target (a tree): at γ = α = β = 1 the minimum of eq (138) is −log Z, Z = 1 + Σψ = 5.
  TempDir dir;
  dir.write("w.csv", "0.5,2,1.5\n");
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "fbp", "--weights", "w.csv", "--format", "json"});
  INFO("stdout: " << result.out);
  CHECK(JsonChecker(result.out).valid());
  const auto at = result.out.find("\"free_energy\": ");
  REQUIRE(at != std::string::npos);
  CHECK(std::strtod(result.out.c_str() + at + 15, nullptr) == Approx(-std::log(5.0)).epsilon(1e-12));
  // Algorithms without a free energy leave the field out.
  const CliResult bp = run_ok(dir, {"solve", "--algorithm", "bp", "--weights", "w.csv", "--format", "json"});
  CHECK_FALSE(contains(bp.out, "free_energy"));
}

// ---------------------------------------------------------------------------------------------
// solve --time

TEST_CASE("cli solve --time: one CSV row with a positive median inside its percentiles", "[cli][solve]") {
  // A tiny budget keeps the test fast; at least --time-min-samples batches are timed anyway.
  TempDir dir;
  dir.write("w.csv", kWeights2x2);
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "bp:delta=1e-9,check_every=1", "--weights", "w.csv",
                                        "--time", "--time-budget", "0.05", "--time-min-samples", "12"});
  INFO("stdout: " << result.out);
  CHECK(result.err.empty());
  const auto lines = split_lines(result.out);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0] == "algorithm,targets,measurements,solves,samples,batch,median_us,p10_us,p90_us,median_interval,stable");
  const auto fields = parse_csv_line(lines[1]);
  REQUIRE(fields.size() == 11);
  CHECK(fields[0] == "bp:delta=1e-9,check_every=1");  // quoted in the file, one field
  CHECK(fields[1] == "2");
  CHECK(fields[2] == "2");
  const long long solves = std::stoll(fields[3]), samples = std::stoll(fields[4]), batch = std::stoll(fields[5]);
  CHECK(samples >= 12);
  CHECK(solves == samples * batch);
  const double median = to_double(fields[6]), p10 = to_double(fields[7]), p90 = to_double(fields[8]);
  CHECK(median > 0.0);
  CHECK(median < 1e5);  // a 2×2 BP takes microseconds, not a tenth of a second
  CHECK(p10 <= median);
  CHECK(median <= p90);
  CHECK(to_double(fields[9]) >= 0.0);
  CHECK((fields[10] == "0" || fields[10] == "1"));
  // Batches double until one lasts 1 ms: a power of two, and many microsecond solves.
  CHECK(batch > 1);
  CHECK((batch & (batch - 1)) == 0);
}

TEST_CASE("cli solve --time --format json parses and reports the same fields", "[cli][solve]") {
  TempDir dir;
  dir.write("w.csv", kWeights2x2);
  const CliResult result = run_ok(dir, {"solve", "--algorithm", "exact", "--weights", "w.csv", "--time", "--format",
                                        "json", "--time-budget", "0.02"});
  INFO("stdout: " << result.out);
  CHECK(JsonChecker(result.out).valid());
  for (const char* key : {"\"algorithm\": \"exact\"", "\"solves\": ", "\"samples\": ", "\"batch\": ", "\"median_us\": ",
                          "\"p10_us\": ", "\"p90_us\": ", "\"median_interval\": ", "\"stable\": "}) {
    INFO("json should hold " << key);
    CHECK(contains(result.out, key));
  }
  const auto at = result.out.find("\"median_us\": ");
  REQUIRE(at != std::string::npos);
  CHECK(std::strtod(result.out.c_str() + at + 13, nullptr) > 0.0);
  CHECK(std::strtoll(result.out.c_str() + result.out.find("\"samples\": ") + 11, nullptr, 10) >= 10);
}

TEST_CASE("cli solve --time: bad combinations are one-line errors", "[cli][solve]") {
  TempDir dir;
  dir.write("w.csv", kWeights2x2);
  const std::vector<std::string> base = {"solve", "--algorithm", "bp", "--weights", "w.csv"};
  const auto with = [&base](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  expect_error(dir, with({"--time-budget", "1"}), {"--time-budget", "--time"});
  expect_error(dir, with({"--time-min-samples", "5"}), {"--time-min-samples", "--time"});
  expect_error(dir, with({"--time", "--time-budget", "0"}), {"--time-budget", "0"});
  expect_error(dir, with({"--time", "--time-budget", "-1"}), {"--time-budget"});
  expect_error(dir, with({"--time", "--time-budget", "soon"}), {"time-budget", "soon"});
  expect_error(dir, with({"--time", "--time-min-samples", "0"}), {"--time-min-samples", "0"});
  expect_error(dir, with({"--time", "--format", "xml"}), {"format", "xml"});
}

TEST_CASE("cli solve --time: a refused problem exits 3 without timing", "[cli][solve]") {
  TempDir dir;
  std::string ones;
  for (int i = 0; i < 6; ++i) ones += "1,1,1,1,1,1\n";
  dir.write("dense.csv", ones);
  const CliResult result = run_dabench(dir, {"solve", "--algorithm", "exact:max_events=10", "--weights", "dense.csv", "--time"});
  CHECK(result.status == 3);
  CHECK(result.out.empty());
  CHECK(contains(result.err, "skipped:"));
}

// ---------------------------------------------------------------------------------------------
// run: errors (each leaves the working folder untouched: no output folder, no file)

TEST_CASE("cli run: the good base experiment runs", "[cli][run]") {
  // The error cases below are this experiment with one thing broken.
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  run_ok(dir, {"run", "e.ini", "--threads", "1"});
  CHECK(dir.exists("out/trials.csv"));
  CHECK(dir.exists("out/summary.csv"));
  CHECK(dir.exists("out/meta.json"));
}

TEST_CASE("cli run: bad experiment files are rejected before any output", "[cli][run]") {
  TempDir dir;
  SECTION("missing experiment file") {
    expect_error(dir, {"run", "nothere.ini"}, {"nothere.ini"});
  }
  SECTION("experiment path is a folder") {
    std::filesystem::create_directories(dir.work() / "folder.ini");
    expect_error(dir, {"run", "folder.ini"}, {"folder.ini"});
  }
  SECTION("experiment path is a device") {
    expect_error(dir, {"run", "/dev/full"}, {"/dev/full", "not a regular file"});
    expect_error(dir, {"run", "/dev/zero"}, {"/dev/zero", "not a regular file"});
  }
  SECTION("experiment file too large") {
    dir.write("huge.ini", std::string((1u << 20) + 1, '#'));
    expect_error(dir, {"run", "huge.ini"}, {"huge.ini", "at most 1048576 bytes"});
  }
  SECTION("malformed INI line") {
    dir.write("e.ini", experiment_with("this line has no equals sign\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "this line has no equals sign"});
  }
  SECTION("unknown top-level key") {
    dir.write("e.ini", experiment_with("colour = blue\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "colour"});
  }
  SECTION("unknown section") {
    dir.write("e.ini", experiment_with("", "[sweeps]\nspacing = 1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "sweeps"});
  }
  SECTION("unknown scenario") {
    std::string text = kGoodExperiment;
    text.replace(text.find("grid"), 4, "nosuchscenario");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchscenario"});
  }
  SECTION("missing scenario") {
    std::string text = kGoodExperiment;
    text.erase(text.find("scenario = grid\n"), 16);
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "scenario"});
  }
  SECTION("unknown scenario parameter in [scenario]") {
    dir.write("e.ini", experiment_with("", "[scenario]\nwidth = 3\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "width"});
  }
  SECTION("unknown scenario parameter in [sweep]") {
    dir.write("e.ini", experiment_with("", "[sweep]\nheight = 1,2\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "height"});
  }
  SECTION("pd out of range") {
    dir.write("e.ini", experiment_with("", "[scenario]\npd = 1.2\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "pd", "1.2"});
  }
  SECTION("negative spacing in a sweep") {
    dir.write("e.ini", experiment_with("", "[sweep.more]\nspacing = 2, -1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "spacing", "-1"});
  }
  SECTION("rows = 0") {
    dir.write("e.ini", experiment_with("", "[scenario]\nrows = 0\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "rows"});
  }
  SECTION("non-numeric scenario value") {
    dir.write("e.ini", experiment_with("", "[scenario]\nlambda_fa = lots\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "lambda_fa", "lots"});
  }
  SECTION("trials = 0") {
    std::string text = kGoodExperiment;
    text.replace(text.find("trials = 3"), 10, "trials = 0");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "trials"});
  }
  SECTION("unknown algorithm") {
    dir.write("e.ini", experiment_with("algorithm = nosuchalgo\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchalgo"});
  }
  SECTION("unknown algorithm parameter") {
    dir.write("e.ini", experiment_with("algorithm = bp:tolerance=1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "tolerance"});
  }
  SECTION("unknown reference") {
    std::string text = kGoodExperiment;
    text.replace(text.find("reference = exact"), 17, "reference = nosuchref");
    dir.write("e.ini", text);
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "nosuchref"});
  }
  SECTION("range with zero step") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 0:0:10\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "0:0:10"});
  }
  SECTION("range with two parts") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 0:1\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "0:1"});
  }
  SECTION("tie to an unswept key") {
    dir.write("e.ini", experiment_with("", "[sweep.b]\nspacing = 1,2\ncols = @rows\n"));
    expect_error(dir, {"run", "e.ini"}, {"e.ini", "@rows"});
  }
}

TEST_CASE("cli run: bad options are rejected before any output", "[cli][run]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  SECTION("--trials 0") {
    expect_error(dir, {"run", "e.ini", "--trials", "0"}, {"trials"});
  }
  SECTION("--threads 0") {
    expect_error(dir, {"run", "e.ini", "--threads", "0"}, {"threads"});
  }
  SECTION("--seed -1") {
    expect_error(dir, {"run", "e.ini", "--seed", "-1"}, {"seed"});
  }
  SECTION("--trials abc") {
    expect_error(dir, {"run", "e.ini", "--trials", "abc"}, {"trials"});
  }
  SECTION("--resume and --force together") {
    expect_error(dir, {"run", "e.ini", "--resume", "--force"}, {"--resume", "--force"});
  }
  SECTION("no experiment") {
    expect_error(dir, {"run"}, {"experiment"});
  }
  SECTION("two experiments") {
    expect_error(dir, {"run", "e.ini", "e.ini"}, {});
  }
}

TEST_CASE("cli run: a folder holding a run is refused and left byte-identical", "[cli][run]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  run_ok(dir, {"run", "e.ini", "--threads", "1"});
  REQUIRE(dir.exists("out/trials.csv"));

  SECTION("without --resume or --force") {
    expect_error(dir, {"run", "e.ini"}, {"out", "--resume", "--force"});
  }
  SECTION("with --out naming the same folder") {
    expect_error(dir, {"run", "e.ini", "--out", "out"}, {"out"});
  }
  SECTION("only meta.json left") {
    std::filesystem::remove(dir.work() / "out" / "trials.csv");
    expect_error(dir, {"run", "e.ini"}, {"out"});
  }
  SECTION("--resume with a different seed") {
    expect_error(dir, {"run", "e.ini", "--resume", "--seed", "6"}, {"out", "resume"});
  }
  SECTION("--resume with different trials") {
    expect_error(dir, {"run", "e.ini", "--resume", "--trials", "4"}, {"out", "resume"});
  }
  SECTION("--resume with a different experiment") {
    std::string text = kGoodExperiment;
    text.replace(text.find("spacing = 1, 2"), 14, "spacing = 1, 3");
    dir.write("e2.ini", text);
    expect_error(dir, {"run", "e2.ini", "--resume"}, {"out", "resume"});
  }
  SECTION("--resume with a different algorithm list") {
    dir.write("e2.ini", experiment_with("algorithm = bp:delta=1e-6\n"));
    expect_error(dir, {"run", "e2.ini", "--resume"}, {"out", "resume"});
  }
}

// ---------------------------------------------------------------------------------------------
// run --shard and merge

namespace {

// Columns of trials.csv but time_us.
CsvTable without_time(const CsvTable& table) {
  const std::size_t time = table.column("time_us");
  CsvTable kept = table;
  kept.header.erase(kept.header.begin() + static_cast<std::ptrdiff_t>(time));
  for (auto& row : kept.rows) row.erase(row.begin() + static_cast<std::ptrdiff_t>(time));
  return kept;
}

// kGoodExperiment (6 items: one block, so shards 2 and 3 of 3 are empty) as shards s1..s3 of 3.
void run_three_shards(const TempDir& dir) {
  dir.write("e.ini", kGoodExperiment);
  for (const char* k : {"1", "2", "3"}) run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", std::string(k) + "/3", "--out", std::string("s") + k});
}

}  // namespace

TEST_CASE("cli merge: shards merged from the command line equal the run", "[cli][shard]") {
  TempDir dir;
  run_three_shards(dir);
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--out", "full"});
  const CliResult merged = run_ok(dir, {"merge", "m", "s3", "s1", "s2"});
  CHECK(contains(merged.err, "merged 3 shards, 6 trials"));
  CHECK(without_time(parse_csv(dir.read("m/trials.csv"))).rows == without_time(parse_csv(dir.read("full/trials.csv"))).rows);
  CHECK(dir.exists("m/summary.csv"));
  CHECK(contains(dir.read("m/meta.json"), "\"processes\": 3"));
  // Without --out a shard goes beside the experiment's output folder.
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/2"});
  CHECK(dir.exists("out-shard-2-of-2/trials.csv"));
  CHECK(contains(dir.read("out-shard-2-of-2/meta.json"), "\"shard\": \"2/2\""));
  // --force replaces a merged run.
  expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"m", "--force"});
  run_ok(dir, {"merge", "m", "s1", "s2", "s3", "--force"});
}

TEST_CASE("cli merge: missing, duplicated, foreign or incomplete shards are one-line errors", "[cli][shard]") {
  TempDir dir;
  run_three_shards(dir);
  SECTION("missing") { expect_error(dir, {"merge", "m", "s1", "s3"}, {"missing", "2/3"}); }
  SECTION("duplicated") { expect_error(dir, {"merge", "m", "s1", "s2", "s3", "s2"}, {"2/3", "twice"}); }
  SECTION("another seed") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/3", "--seed", "6", "--out", "f2"});
    expect_error(dir, {"merge", "m", "s1", "f2", "s3"}, {"f2", "another run"});
  }
  SECTION("another experiment") {
    std::string text = kGoodExperiment;
    text.replace(text.find("spacing = 1, 2"), 14, "spacing = 1, 3");
    dir.write("e2.ini", text);
    run_ok(dir, {"run", "e2.ini", "--threads", "1", "--shard", "3/3", "--out", "f3"});
    expect_error(dir, {"merge", "m", "s1", "s2", "f3"}, {"f3", "another run"});
  }
  SECTION("another split") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "2/2", "--out", "h2"});
    expect_error(dir, {"merge", "m", "s1", "h2", "s3"}, {"h2", "2/2"});
  }
  SECTION("not a shard") {
    run_ok(dir, {"run", "e.ini", "--threads", "1", "--out", "full"});
    expect_error(dir, {"merge", "m", "s1", "full", "s3"}, {"full", "not a shard"});
  }
  SECTION("incomplete") {
    std::string meta = dir.read("s2/meta.json");
    meta.replace(meta.find("\"status\": \"complete\""), 20, "\"status\": \"interrupted\"");
    dir.write("s2/meta.json", meta);
    expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"s2", "interrupted", "--resume"});
  }
  SECTION("rows of another shard") {
    dir.write("s3/trials.csv", dir.read("s1/trials.csv"));
    expect_error(dir, {"merge", "m", "s1", "s2", "s3"}, {"s3/trials.csv", "shard 3/3"});
  }
  SECTION("a split into a million, one shard given: the first eight missing named, the rest counted") {
    std::string meta = dir.read("s1/meta.json");
    meta.replace(meta.find("\"shard\": \"1/3\""), 14, "\"shard\": \"1/1000000\"");
    dir.write("s1/meta.json", meta);
    expect_error(dir, {"merge", "m", "s1"}, {"shards missing: 2/1000000, 3/1000000", "9/1000000 and 999991 more",
                                            "(given 1 of 1000000)"});
  }
  SECTION("not a folder") { expect_error(dir, {"merge", "m", "s1", "nothere", "s3"}, {"nothere", "meta.json"}); }
  SECTION("no shards") { expect_error(dir, {"merge", "m"}, {"merge", "shard folders"}); }
  SECTION("into a shard") { expect_error(dir, {"merge", "s1", "s1", "s2", "s3"}, {"s1", "shard 1/3"}); }
}

TEST_CASE("cli run --shard: bad values and a resume of another shard are one-line errors", "[cli][shard]") {
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "-1/2"}) {
    INFO("--shard " << bad);
    expect_error(dir, {"run", "e.ini", "--shard", bad}, {"--shard", bad});
  }
  run_ok(dir, {"run", "e.ini", "--threads", "1", "--shard", "1/2", "--out", "s"});
  expect_error(dir, {"run", "e.ini", "--shard", "2/2", "--out", "s", "--resume"}, {"s", "shard 1/2", "shard 2/2"});
  expect_error(dir, {"run", "e.ini", "--out", "s", "--resume"}, {"s", "shard 1/2", "no shard"});
}

// ---------------------------------------------------------------------------------------------
// commands

TEST_CASE("cli: unknown or missing command fails without stdout", "[cli]") {
  TempDir dir;
  const auto before = snapshot(dir.work());
  SECTION("unknown command") {
    const CliResult result = run_dabench(dir, {"frobnicate"});
    CHECK(result.status != 0);
    CHECK(result.out.empty());
    REQUIRE(!result.err.empty());
    CHECK(contains(split_lines(result.err)[0], "frobnicate"));
  }
  SECTION("no command") {
    const CliResult result = run_dabench(dir, {});
    CHECK(result.status != 0);
    CHECK(result.out.empty());
    REQUIRE(!result.err.empty());
    CHECK(contains(split_lines(result.err)[0], "command"));
  }
  CHECK(snapshot(dir.work()) == before);
}

// DESIGN.md: "on bad input a one-line message". The unknown/missing-command paths also print
// the usage text (5 lines) on stderr.
TEST_CASE("cli: unknown or missing command prints exactly one stderr line", "[cli]") {
  TempDir dir;
  CHECK(count_newlines(run_dabench(dir, {"frobnicate"}).err) == 1);
  CHECK(count_newlines(run_dabench(dir, {}).err) == 1);
}

TEST_CASE("cli list: names algorithms with parameters and scenarios and experiments", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"list"});
  CHECK(result.err.empty());
  for (const char* word : {"bp", "exact", "grid", "check_every", "delta", "max_events", "spacing", "quickstart.ini"}) {
    INFO("list should mention " << word);
    CHECK(contains(result.out, word));
  }
  CHECK(snapshot(dir.work()).empty());
  // A section's summaries start in one column, however long its longest name.
  const auto summary_column = [&](const std::string& name) {
    const std::size_t line = result.out.find("\n  " + name + " ");
    REQUIRE(line != std::string::npos);
    return result.out.find_first_not_of(' ', line + 3 + name.size()) - line;
  };
  CHECK(summary_column("bp") == summary_column("modified-cheap-jpda"));
}

TEST_CASE("cli help: prints the usage on stdout", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"--help"});
  CHECK(contains(result.out, "dabench solve"));
  CHECK(contains(result.out, "dabench run"));
  CHECK(contains(result.out, "dabench merge"));
  CHECK(contains(result.out, "dabench --version"));
  CHECK(contains(result.out, "dabench COMMAND --help"));
  CHECK(result.err.empty());
}

TEST_CASE("cli help: --help and -h on every command print its usage and options, exit 0", "[cli]") {
  // Each command's own options appear; required options and the experiment are not needed, and
  // --help wins over the other words of a valid command line. Nothing is written.
  TempDir dir;
  dir.write("e.ini", kGoodExperiment);
  const auto before = snapshot(dir.work());
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"list", "--help"}, {"usage: dabench list\n", "--help"}},
      {{"list", "-h"}, {"usage: dabench list\n"}},
      {{"solve", "--help"}, {"usage: dabench solve --algorithm SPEC", "--algorithm", "--weights", "--format", "--pd"}},
      {{"solve", "-h", "--algorithm", "bp"}, {"usage: dabench solve"}},
      {{"run", "--help"}, {"usage: dabench run EXPERIMENT.ini", "--trials", "--threads", "--resume", "--force"}},
      {{"run", "e.ini", "--trials", "2", "-h"}, {"usage: dabench run"}},
      {{"merge", "--help"}, {"usage: dabench merge OUT SHARD_DIR", "--force"}},
  };
  for (const auto& [args, mentions] : cases) {
    std::string shown;
    for (const auto& arg : args) shown += " " + arg;
    INFO("dabench" << shown);
    const CliResult result = run_ok(dir, args);
    CHECK(result.err.empty());
    CHECK(result.out.rfind("usage: dabench " + args[0], 0) == 0);
    for (const auto& part : mentions) {
      INFO("the usage should mention: " << part);
      CHECK(contains(result.out, part));
    }
  }
  CHECK_FALSE(contains(run_ok(dir, {"solve", "--help"}).out, "--resume"));  // its own options only
  CHECK(snapshot(dir.work()) == before);
}

TEST_CASE("cli --version: program name, project version and the build's git commit", "[cli]") {
  TempDir dir;
  const CliResult result = run_ok(dir, {"--version"});
  CHECK(result.err.empty());
  const dabench::BuildInfo& build = dabench::build_info();
  CHECK(build.version == DABENCH_PROJECT_VERSION);  // CMake's project(VERSION) reaches the program
  const std::string expected =
      build.git_commit == "unknown"
          ? fmt::format("dabench {}\n", DABENCH_PROJECT_VERSION)
          : fmt::format("dabench {} (git {}{})\n", DABENCH_PROJECT_VERSION, build.git_commit,
                        build.source == dabench::Provenance::modified ? ", modified source" : "");
  CHECK(result.out == expected);
  CHECK(snapshot(dir.work()).empty());
}

TEST_CASE("cli: extra words after list, --help or --version are one-line errors", "[cli]") {
  TempDir dir;
  expect_error(dir, {"list", "extra"}, {"list"});
  expect_error(dir, {"--version", "extra"}, {"--version", "extra"});
  expect_error(dir, {"--help", "extra"}, {"extra"});
}
