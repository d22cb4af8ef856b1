// harness/core/json.hpp: json_value reads back what JsonObject writes — strings with every
// escape JsonObject makes (quote, backslash, newline, tab, control characters as \u00XX),
// numbers, booleans and null as written — takes the first occurrence of a key, and reports an
// absent key or a cut value as nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "harness/core/json.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench;

TEST_CASE("json_value reads back JsonObject's fields", "[json]") {
  const std::string tricky = "a \"quoted\" \\ path\nline two\ttab \x01 end";
  JsonObject json;
  json.add("text", tricky).add("count", 42LL).add("ratio", 0.125).add("flag", true).add("missing", std::nan(""));
  json.add("shard", "2/3").add("shard_items", 96LL);
  const std::string text = json.str();
  CHECK(json_value(text, "text") == tricky);
  CHECK(json_value(text, "count") == "42");
  CHECK(json_value(text, "ratio") == "0.125");
  CHECK(json_value(text, "flag") == "true");
  CHECK(json_value(text, "missing") == "null");
  CHECK(json_value(text, "shard") == "2/3");  // not shard_items
  CHECK(json_value(text, "shard_items") == "96");
  CHECK_FALSE(json_value(text, "absent").has_value());
  CHECK_FALSE(json_value(R"({"text": "cut)", "text").has_value());
  CHECK(json_value("{\"a\": \"x\",\n\"a\": \"y\"}", "a") == "x");  // the first occurrence
}

}  // namespace DABENCH_TEST_FILE
