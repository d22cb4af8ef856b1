#include "harness/core/json.hpp"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "harness/core/utf8.hpp"

namespace dabench {

// Bytes that are not UTF-8 (a path in another encoding) become U+FFFD: JSON text is Unicode.
std::string JsonObject::quote(std::string_view text) {
  std::string out = "\"";
  for (std::size_t at = 0; at < text.size();) {
    const char c = text[at];
    const std::size_t length = static_cast<unsigned char>(c) < 0x80 ? 1 : utf8_length(text, at);
    if (length == 0) {
      out += "\\ufffd";
      ++at;
      continue;
    }
    if (length > 1) {
      out.append(text.substr(at, length));
      at += length;
      continue;
    }
    ++at;
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

std::optional<std::string> json_value(std::string_view json, std::string_view key) {
  const std::string label = JsonObject::quote(key) + ": ";
  const auto at = json.find(label);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t k = at + label.size();
  if (k >= json.size()) return std::nullopt;
  if (json[k] != '"') {
    const auto end = json.find_first_of(",\n}", k);
    if (end == std::string_view::npos) return std::nullopt;
    return std::string(json.substr(k, end - k));
  }
  std::string text;
  for (++k; k < json.size(); ++k) {
    const char c = json[k];
    if (c == '"') return text;
    if (c != '\\') {
      text += c;
      continue;
    }
    if (++k >= json.size()) return std::nullopt;
    switch (json[k]) {
      case 'n': text += '\n'; break;
      case 'r': text += '\r'; break;
      case 't': text += '\t'; break;
      case 'b': text += '\b'; break;
      case 'f': text += '\f'; break;
      case 'u': {  // JsonObject writes control characters and U+FFFD (for bytes not UTF-8) this way
        if (k + 4 >= json.size()) return std::nullopt;
        const std::string hex(json.substr(k + 1, 4));
        char* end = nullptr;
        const long code = std::strtol(hex.c_str(), &end, 16);
        if (end != hex.c_str() + 4 || (code >= 0xD800 && code <= 0xDFFF)) return std::nullopt;
        if (code < 0x80) {
          text += static_cast<char>(code);
        } else if (code < 0x800) {
          text += static_cast<char>(0xC0 | (code >> 6));
          text += static_cast<char>(0x80 | (code & 0x3F));
        } else {
          text += static_cast<char>(0xE0 | (code >> 12));
          text += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
          text += static_cast<char>(0x80 | (code & 0x3F));
        }
        k += 4;
        break;
      }
      default: text += json[k];  // \" \\ \/
    }
  }
  return std::nullopt;
}

}  // namespace dabench
