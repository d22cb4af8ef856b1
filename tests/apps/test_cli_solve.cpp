// The command-line contract of `dabench solve` (DESIGN.md, "Command line"), on the real
// executable: it prints target,measurement,probability with n·(m+1) rows, 1-based targets,
// measurement 0 = missed detection, rows summing to 1, and the closed-form marginals of a
// hand-computable 2×2 problem (also in --format json); `solve --time` prints one parseable row
// (or JSON object) with a positive median inside its percentiles and the repetition count; every
// error is one stderr line that names the problem (and the file/line where there is one).
#include <catch2/catch.hpp>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/support/cli_contract.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;

namespace {

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

// A zero missed-detection weight in the tcl layout (Pd = 1: the TCL answers such problems): exact
// and ehm give the marginals with that target always detected; bp, in the ψ_i(0) = 1 form,
// exits 3 with skipped:zero_miss_weight; a problem no event can satisfy, skipped:infeasible.
TEST_CASE("cli solve: a zero missed-detection weight (tcl) is a target that must be detected", "[cli][solve]") {
  TempDir dir;
  dir.write("tcl.csv", "0.2,0.4,0,0,0\n0.3,0,0.6,0,0.5\n");  // target 1: Pd = 1
  dir.write("infeasible.csv", "1,0,0\n1,0,0\n");              // both must take measurement 1
  for (const char* spec : {"exact", "ehm"}) {
    const CliResult result = run_ok(dir, {"solve", "--algorithm", spec, "--weights", "tcl.csv", "--layout", "tcl"});
    const auto rows = check_solve_csv(result.out, 2, 3);
    CHECK(rows[0].probability == 0.0);                                  // p(a_1 = 0)
    CHECK(rows[1].probability == Approx(0.22 / 0.78).epsilon(1e-14));  // hand-computed: Z = 0.78
  }
  const CliResult bp = run_dabench(dir, {"solve", "--algorithm", "bp", "--weights", "tcl.csv", "--layout", "tcl"});
  CHECK(bp.status == 3);
  CHECK(bp.err == "dabench: bp: skipped:zero_miss_weight (the algorithm refused this problem)\n");
  const CliResult none = run_dabench(dir, {"solve", "--algorithm", "exact", "--weights", "infeasible.csv", "--layout", "tcl"});
  CHECK(none.status == 3);
  CHECK(none.err == "dabench: exact: skipped:infeasible (the algorithm refused this problem)\n");
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

}  // namespace DABENCH_TEST_FILE
