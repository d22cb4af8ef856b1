#include "harness/core/json.hpp"

#include <cmath>

#include <fmt/format.h>

namespace dabench {

std::string JsonObject::quote(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\u{:04x}", static_cast<int>(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

void JsonObject::key(std::string_view name) {
  if (!body_.empty()) body_ += ",\n";
  body_ += "  " + quote(name) + ": ";
}

JsonObject& JsonObject::add(std::string_view name, std::string_view value) {
  key(name);
  body_ += quote(value);
  return *this;
}
JsonObject& JsonObject::add(std::string_view name, double value) {
  key(name);
  body_ += std::isfinite(value) ? fmt::format("{}", value) : std::string("null");
  return *this;
}
JsonObject& JsonObject::add(std::string_view name, long long value) {
  key(name);
  body_ += fmt::format("{}", value);
  return *this;
}
JsonObject& JsonObject::add(std::string_view name, bool value) {
  key(name);
  body_ += value ? "true" : "false";
  return *this;
}
JsonObject& JsonObject::add_raw(std::string_view name, std::string_view json) {
  key(name);
  body_ += json;
  return *this;
}

}  // namespace dabench
