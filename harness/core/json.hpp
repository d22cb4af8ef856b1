#pragma once
// A small JSON object writer for meta.json: flat keys, strings/numbers/bools, in insertion order;
// and json_value, which reads a field back from what JsonObject wrote.
#include <optional>
#include <string>
#include <string_view>

namespace dabench {

class JsonObject {
 public:
  JsonObject& add(std::string_view key, std::string_view value);
  JsonObject& add(std::string_view key, const char* value) { return add(key, std::string_view(value)); }
  JsonObject& add(std::string_view key, double value);
  JsonObject& add(std::string_view key, long long value);
  JsonObject& add(std::string_view key, bool value);
  JsonObject& add_raw(std::string_view key, std::string_view json);  // value already JSON
  std::string str() const { return body_.empty() ? "{}\n" : "{\n" + body_ + "\n}\n"; }

  static std::string quote(std::string_view text);

 private:
  void key(std::string_view name);
  std::string body_;
};

// The value of the first `"key": ` in `json` as JsonObject writes it: a string unescaped, else
// the number, true, false or null as written; nothing if the key is absent or the value cut.
std::optional<std::string> json_value(std::string_view json, std::string_view key);

}  // namespace dabench
