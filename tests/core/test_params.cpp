// Tests of the configuration edge (harness/core/params.hpp, harness/core/registry.hpp, harness/single_scan/registry.hpp): SPEC parsing,
// strict number parsing, ParamList binding/formatting, and the errors of
// make_single_scan_solver. Every rejected input must throw dabench::InputError whose message
// names the offending key or value (Ceres style: say which field broke which rule).
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"
#include "harness/single_scan/registry.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

using dabench::test::input_error_message;

namespace {

std::string spec_error(const std::string& text) {
  return input_error_message([&] { parse_spec(text); });
}
std::string solver_error(const std::string& text) {
  return input_error_message([&] { make_single_scan_solver(text); });
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string resolved(const std::string& algorithm, const std::vector<KeyValue>& settings, const std::string& key) {
  const auto* entry = single_scan_algorithm_registry().find(algorithm);
  REQUIRE(entry != nullptr);
  for (const KeyValue& kv : entry->resolve(settings)) {
    if (kv.key == key) return kv.value;
  }
  FAIL("no parameter " << key << " in " << algorithm);
  return {};
}

double resolved_double(const std::string& algorithm, const std::vector<KeyValue>& settings, const std::string& key) {
  double value = 0.0;
  REQUIRE(parse_double(resolved(algorithm, settings, key), value));
  return value;
}

}  // namespace

TEST_CASE("params: parse_spec accepts names and key=value lists", "[params]") {
  SECTION("name only") {
    const Spec spec = parse_spec("bp");
    CHECK(spec.name == "bp");
    CHECK(spec.settings.empty());
  }
  SECTION("name with settings, in order") {
    const Spec spec = parse_spec("bp:delta=1e-6,check_every=10");
    CHECK(spec.name == "bp");
    REQUIRE(spec.settings.size() == 2);
    CHECK(spec.settings[0].key == "delta");
    CHECK(spec.settings[0].value == "1e-6");
    CHECK(spec.settings[1].key == "check_every");
    CHECK(spec.settings[1].value == "10");
  }
  SECTION("whitespace around every token is ignored") {
    const Spec spec = parse_spec("  bp : delta = 1e-6 ,  check_every= 10 \t");
    CHECK(spec.name == "bp");
    REQUIRE(spec.settings.size() == 2);
    CHECK(spec.settings[0].key == "delta");
    CHECK(spec.settings[0].value == "1e-6");
    CHECK(spec.settings[1].key == "check_every");
    CHECK(spec.settings[1].value == "10");
  }
  SECTION("empty value is passed through (rejected later by the typed parser)") {
    const Spec spec = parse_spec("bp:delta=");
    REQUIRE(spec.settings.size() == 1);
    CHECK(spec.settings[0].value.empty());
  }
}

TEST_CASE("params: parse_spec rejects malformed specs and names the problem", "[params]") {
  CHECK(contains(spec_error("bp:delta"), "delta"));               // missing '='
  CHECK(contains(spec_error("bp:=1"), "=1"));                     // empty key
  CHECK(contains(spec_error("bp:delta=1,delta=2"), "delta"));     // repeated key
  CHECK(contains(spec_error(":x=1"), ":x=1"));                    // empty name
  CHECK(contains(spec_error(""), "empty"));
  CHECK(contains(spec_error("bp:delta=1,"), "bp:delta=1,"));      // trailing comma: empty item
}

TEST_CASE("params: parse_double is strict", "[params]") {
  double value = -1.0;
  CHECK(parse_double("1e-3", value));
  CHECK(value == 1e-3);
  CHECK(parse_double(" +2.5 ", value));
  CHECK(value == 2.5);
  CHECK(parse_double("-0.125", value));
  CHECK(value == -0.125);
  value = 42.0;
  CHECK_FALSE(parse_double("nan", value));
  CHECK_FALSE(parse_double("inf", value));
  CHECK_FALSE(parse_double("-inf", value));
  CHECK_FALSE(parse_double("1e400", value));  // overflows: not finite
  CHECK_FALSE(parse_double("2.5x", value));
  CHECK_FALSE(parse_double("abc", value));
  CHECK_FALSE(parse_double("", value));
  CHECK_FALSE(parse_double("   ", value));
  CHECK_FALSE(parse_double("++1", value));
  CHECK_FALSE(parse_double("1,5", value));
  CHECK(value == 42.0);  // untouched on failure
}

TEST_CASE("params: parse_int64 is strict and accepts integral scientific notation", "[params]") {
  std::int64_t value = -1;
  CHECK(parse_int64("12", value));
  CHECK(value == 12);
  CHECK(parse_int64(" 7 ", value));
  CHECK(value == 7);
  CHECK(parse_int64("+3", value));
  CHECK(value == 3);
  CHECK(parse_int64("-4", value));
  CHECK(value == -4);
  CHECK(parse_int64("1e6", value));
  CHECK(value == 1000000);
  CHECK(parse_int64("2.5e3", value));  // 2500 is integral
  CHECK(value == 2500);
  CHECK(parse_int64("9007199254740991", value));  // 2^53 - 1, exact integer path
  CHECK(value == 9007199254740991LL);
  value = 99;
  CHECK_FALSE(parse_int64("1.5e0", value));  // 1.5 is not an integer
  CHECK_FALSE(parse_int64("1.5", value));
  CHECK_FALSE(parse_int64("1e-3", value));
  CHECK_FALSE(parse_int64("1e20", value));   // beyond the exactly representable range
  CHECK_FALSE(parse_int64("abc", value));
  CHECK_FALSE(parse_int64("", value));
  CHECK_FALSE(parse_int64("12abc", value));
  CHECK_FALSE(parse_int64("0x10", value));
  CHECK_FALSE(parse_int64("nan", value));
  CHECK(value == 99);  // untouched on failure
}

TEST_CASE("params: ParamList binds and assigns and formats typed fields", "[params]") {
  int count = 5;
  std::int64_t budget = 100;
  double rate = 0.25;
  bool flag = false;
  ParamList params;
  params.add("count", count, "an int");
  params.add("budget", budget, "an int64");
  params.add("rate", rate, "a real");
  params.add("flag", flag, "a bool");
  REQUIRE(params.entries().size() == 4);
  CHECK(params.known_keys() == "count, budget, rate, flag");
  CHECK(params.find("rate") != nullptr);
  CHECK(params.find("nope") == nullptr);

  params.assign("count", "1e3", "toy");
  CHECK(count == 1000);
  params.assign("budget", "5000000000", "toy");  // beyond int32
  CHECK(budget == 5000000000LL);
  params.assign("rate", "1e-7", "toy");
  CHECK(rate == 1e-7);
  params.assign("flag", "true", "toy");
  CHECK(flag);
  params.assign("flag", "0", "toy");
  CHECK_FALSE(flag);
  params.assign("flag", "yes", "toy");
  CHECK(flag);

  // Shortest round-trip formatting: parsing the text gives back the same double.
  rate = 0.1 + 0.2;
  double back = 0.0;
  REQUIRE(parse_double(ParamList::format(*params.find("rate")), back));
  CHECK(back == rate);
  CHECK(ParamList::format(*params.find("count")) == "1000");
  CHECK(ParamList::format(*params.find("flag")) == "true");

  const std::string unknown = input_error_message([&] { params.assign("cnt", "1", "toy"); });
  CHECK(contains(unknown, "cnt"));
  CHECK(contains(unknown, "toy"));
  CHECK(contains(unknown, "count"));  // lists the known keys
  CHECK(contains(input_error_message([&] { params.assign("count", "5000000000", "toy"); }), "5000000000"));
  CHECK(contains(input_error_message([&] { params.assign("flag", "maybe", "toy"); }), "maybe"));
  CHECK(contains(input_error_message([&] { params.assign("rate", "inf", "toy"); }), "rate"));
  CHECK(count == 1000);  // failed assignments leave fields unchanged
  CHECK(rate == 0.1 + 0.2);

  const std::string listing = params.describe("  ");
  CHECK(contains(listing, "count"));
  CHECK(contains(listing, "an int64"));
}

TEST_CASE("params: algorithm defaults and settings resolve", "[params]") {
  // Paper defaults (Fig. 3: N in 5..20; δ = 1e-3 as in Fig. 2) and the exact oracle's.
  CHECK(resolved("bp", {}, "check_every") == "5");
  CHECK(resolved_double("bp", {}, "delta") == 1e-3);
  CHECK(resolved_double("exact", {}, "threshold") == 0.0);
  CHECK(resolved_double("exact", {}, "max_events") == 1e8);

  CHECK(resolved_double("bp", {{"delta", "1e-6"}}, "delta") == 1e-6);
  CHECK(resolved("bp", {{"check_every", "10"}}, "check_every") == "10");
  CHECK(resolved_double("bp", {{"check_every", "10"}}, "delta") == 1e-3);  // others keep defaults

  CHECK(make_single_scan_solver("bp") != nullptr);
  CHECK(make_single_scan_solver("bp:delta=1e-6,check_every=10") != nullptr);
  CHECK(make_single_scan_solver(" exact : threshold = 1e-3 , max_events = 1e6 ") != nullptr);
}

TEST_CASE("params: make_single_scan_solver rejects bad specs and names the key or value", "[params]") {
  SECTION("unknown algorithm") {
    const std::string message = solver_error("nosuchalgo");
    CHECK(contains(message, "nosuchalgo"));
    CHECK(contains(message, "bp"));  // lists what is known
  }
  SECTION("unknown key") {
    const std::string message = solver_error("bp:tolerance=1e-3");
    CHECK(contains(message, "tolerance"));
    CHECK(contains(message, "delta"));  // lists the known keys
  }
  SECTION("malformed values") {
    for (const auto& [spec, key, value] : {std::tuple{"bp:delta=abc", "delta", "abc"},
                                           std::tuple{"bp:check_every=1.5", "check_every", "1.5"},
                                           std::tuple{"bp:delta=nan", "delta", "nan"},
                                           std::tuple{"bp:delta=inf", "delta", "inf"},
                                           std::tuple{"bp:delta=", "delta", "delta"},
                                           std::tuple{"bp:check_every=1e10", "check_every", "1e10"},
                                           std::tuple{"exact:max_events=ten", "max_events", "ten"}}) {
      const std::string message = solver_error(spec);
      INFO(spec << " -> " << message);
      CHECK(contains(message, key));
      CHECK(contains(message, value));
    }
  }
  SECTION("values out of range") {
    for (const auto& [spec, key] : {std::pair{"bp:check_every=0", "check_every"},
                                    std::pair{"bp:check_every=-3", "check_every"},
                                    std::pair{"bp:delta=0", "delta"},
                                    std::pair{"bp:delta=-1", "delta"},
                                    std::pair{"bp:max_iterations=0", "max_iterations"},
                                    std::pair{"exact:max_events=0", "max_events"},
                                    std::pair{"exact:threshold=-1", "threshold"}}) {
      const std::string message = solver_error(spec);
      INFO(spec << " -> " << message);
      CHECK(contains(message, key));
    }
  }
  SECTION("spec syntax errors surface through make_single_scan_solver too") {
    CHECK(contains(solver_error("bp:delta"), "delta"));
    CHECK(contains(solver_error("bp:delta=1,delta=2"), "delta"));
  }
}

}  // namespace DABENCH_TEST_FILE
