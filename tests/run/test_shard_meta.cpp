// harness/run/shard_meta.hpp: a shard's meta.json as `dabench merge` reads it, called on text
// (the fuzz target tests/fuzz/fuzz_shard_meta.cpp drives the same functions with arbitrary bytes):
//  - "K/N" labels: 1 <= K <= N <= 1 000 000, integers only;
//  - a meta.json without a shard label, with a malformed one or with status other than complete
//    is refused in one line naming the folder; `threads` is bounded whatever the file says;
//  - the plan rebuilt from the recorded experiment must give the recorded fingerprint.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "harness/core/json.hpp"
#include "harness/run/shard_meta.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;
using dabench::test::input_error_message;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const char* const kExperiment = "scenario = grid\ntrials = 20\nseed = 3\nreference = exact\nalgorithm = bp\n";

// The meta.json of shard `label` of kExperiment's run, as a run writes its fields.
std::string shard_meta(const std::string& label, const std::string& status, const std::string& fingerprint,
                       const std::string& threads = "2") {
  JsonObject json;
  json.add("status", status).add("fingerprint", fingerprint).add("shard", label).add("experiment_path", "grid.ini");
  json.add("experiment", kExperiment).add("seed", 3LL).add("trials_per_point", 20LL).add_raw("threads", threads);
  json.add("items_done", 4LL).add("shard_items", 8LL);
  return json.str();
}

std::string fingerprint_of_experiment() {
  RunOptions options;
  options.threads = 1;
  return make_run_plan(parse_experiment("grid.ini", kExperiment), options).fingerprint();
}

}  // namespace

TEST_CASE("shard meta: labels K/N with 1 <= K <= N <= 10^6", "[run][shard]") {
  const auto shard = parse_shard_label("2/3");
  REQUIRE(shard);
  CHECK((shard->index == 2 && shard->count == 3));
  CHECK(parse_shard_label("1000000/1000000"));
  for (const char* bad : {"", "/", "3", "0/3", "4/3", "1/0", "-1/3", "1/1000001", "1/99999999999999999999", "1.5/3",
                          "1/3/4", "a/b", "2 /3x"}) {
    INFO(bad);
    CHECK_FALSE(parse_shard_label(bad));
  }
}

TEST_CASE("shard meta: a complete shard is read and its plan rebuilt", "[run][shard]") {
  const std::string fingerprint = fingerprint_of_experiment();
  const ShardMeta shard = parse_shard_meta("s2", shard_meta("2/3", "complete", fingerprint));
  CHECK(shard.label == "2/3");
  CHECK((shard.shard.index == 2 && shard.shard.count == 3));
  CHECK(shard.threads() == 2);
  CHECK(std::isnan(shard.number("wall_seconds")));
  const RunPlan plan = shard_run_plan(shard, "merged");
  CHECK(plan.fingerprint() == fingerprint);
  CHECK(plan.trials == 20);
  CHECK(plan.output == "merged");
}

TEST_CASE("shard meta: what merge refuses, in one line naming the folder", "[run][shard]") {
  const std::string fingerprint = fingerprint_of_experiment();
  const auto refused = [](const std::string& meta) { return input_error_message([&] { parse_shard_meta("s1", meta); }); };
  CHECK(contains(refused("{}\n"), "s1: not a shard"));
  CHECK(contains(refused(shard_meta("0/3", "complete", fingerprint)), "s1/meta.json: malformed shard '0/3'"));
  CHECK(contains(refused(shard_meta("1/2000000", "complete", fingerprint)), "malformed shard"));
  CHECK(contains(refused(shard_meta("1/3", "interrupted", fingerprint)), "s1: shard 1/3 is interrupted (4 of 8 items done)"));
  const ShardMeta foreign = parse_shard_meta("s1", shard_meta("1/3", "complete", "0123456789abcdef"));
  CHECK(contains(input_error_message([&] { shard_run_plan(foreign, "merged"); }),
                 "s1: its experiment now gives fingerprint " + fingerprint + ", not the recorded 0123456789abcdef"));
  const ShardMeta no_seed = parse_shard_meta("s1", "{\"status\": \"complete\", \"shard\": \"1/1\"}");
  CHECK(contains(input_error_message([&] { shard_run_plan(no_seed, "merged"); }), "s1/meta.json: no 'trials_per_point' field"));
}

TEST_CASE("shard meta: threads stays in 1..65536 whatever the file says", "[run][shard]") {
  const std::string fingerprint = fingerprint_of_experiment();
  const auto threads = [&](const std::string& value) {
    return parse_shard_meta("s", shard_meta("1/1", "complete", fingerprint, value)).threads();
  };
  CHECK(threads("8") == 8);
  CHECK(threads("0") == 1);
  CHECK(threads("-5") == 1);
  CHECK(threads("1e300") == 65536);
  CHECK(threads("\"many\"") == 1);
  CHECK(threads("null") == 1);
}

}  // namespace DABENCH_TEST_FILE
