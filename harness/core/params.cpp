#include "harness/core/params.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace dabench {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

bool parse_double(std::string_view text, double& out) {
  text = trim(text);
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return false;
  out = value;
  return true;
}

bool parse_int64(std::string_view text, std::int64_t& out) {
  text = trim(text);
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc() && end == text.data() + text.size()) {
    out = value;
    return true;
  }
  // Scientific notation for large counts, e.g. samples=1e7, as long as it is an integer.
  double as_double = 0.0;
  if (!parse_double(text, as_double) || as_double != std::floor(as_double) ||
      std::fabs(as_double) > 9.0e15) {
    return false;
  }
  out = static_cast<std::int64_t>(as_double);
  return true;
}

const ParamList::Entry* ParamList::find(std::string_view key) const {
  for (const Entry& entry : entries_) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

std::string ParamList::known_keys() const {
  std::string keys;
  for (const Entry& entry : entries_) {
    if (!keys.empty()) keys += ", ";
    keys += entry.key;
  }
  return keys.empty() ? std::string("none") : keys;
}

void ParamList::assign(std::string_view key, std::string_view value, std::string_view owner) const {
  const Entry* entry = find(key);
  if (entry == nullptr) {
    throw InputError(fmt::format("{}: unknown parameter '{}' (known: {})", owner, key, known_keys()));
  }
  const auto bad = [&](std::string_view expected) {
    return InputError(fmt::format("{}: parameter '{}' = '{}' is not {}", owner, key, value, expected));
  };
  if (!entry->choices.empty()) {
    const auto found = std::find(entry->choices.begin(), entry->choices.end(), trim(value));
    if (found == entry->choices.end()) throw bad(fmt::format("one of {}", fmt::join(entry->choices, ", ")));
    *std::get<int*>(entry->target) = static_cast<int>(found - entry->choices.begin());
    return;
  }
  std::visit(
      [&](auto* field) {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_same_v<T, std::string>) {
          *field = std::string(trim(value));
        } else if constexpr (std::is_same_v<T, double>) {
          if (!parse_double(value, *field)) throw bad("a finite number");
        } else if constexpr (std::is_same_v<T, bool>) {
          const std::string_view v = trim(value);
          if (v == "true" || v == "1" || v == "yes") {
            *field = true;
          } else if (v == "false" || v == "0" || v == "no") {
            *field = false;
          } else {
            throw bad("true or false");
          }
        } else {
          std::int64_t parsed = 0;
          if (!parse_int64(value, parsed)) throw bad("an integer");
          if (parsed < std::numeric_limits<T>::min() || parsed > std::numeric_limits<T>::max()) {
            throw bad("an integer in range");
          }
          *field = static_cast<T>(parsed);
        }
      },
      entry->target);
}

std::string ParamList::format(const Entry& entry) {
  if (!entry.choices.empty()) return entry.choices.at(static_cast<std::size_t>(*std::get<int*>(entry.target)));
  return std::visit(
      [](auto* field) -> std::string {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_same_v<T, bool>) {
          return *field ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          return *field;
        } else {
          return fmt::format("{}", *field);
        }
      },
      entry.target);
}

std::string ParamList::describe(std::string_view indent) const {
  std::string text;
  for (const Entry& entry : entries_) {
    const char* type = !entry.choices.empty() ? "name" : std::visit(
        [](auto* field) {
          using T = std::remove_pointer_t<decltype(field)>;
          if constexpr (std::is_same_v<T, double>) return "real";
          else if constexpr (std::is_same_v<T, bool>) return "bool";
          else if constexpr (std::is_same_v<T, std::string>) return "text";
          else return "int";
        },
        entry.target);
    text += fmt::format("{}{:<16} {:<5} = {:<10} {}\n", indent, entry.key, type, format(entry), entry.doc);
  }
  return text;
}

Spec parse_spec(std::string_view text) {
  text = trim(text);
  Spec spec;
  const auto colon = text.find(':');
  spec.name = std::string(trim(text.substr(0, colon)));
  if (spec.name.empty()) throw InputError(fmt::format("empty algorithm name in spec '{}'", text));
  if (colon == std::string_view::npos) return spec;
  std::string_view rest = text.substr(colon + 1);
  std::set<std::string, std::less<>> seen;
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view item = trim(rest.substr(0, comma));
    const auto eq = item.find('=');
    if (eq == std::string_view::npos) {
      throw InputError(fmt::format("spec '{}': expected key=value, got '{}'", text, item));
    }
    KeyValue kv{std::string(trim(item.substr(0, eq))), std::string(trim(item.substr(eq + 1)))};
    if (kv.key.empty()) throw InputError(fmt::format("spec '{}': empty parameter name", text));
    if (!seen.insert(kv.key).second) {
      throw InputError(fmt::format("spec '{}': parameter '{}' given twice", text, kv.key));
    }
    spec.settings.push_back(std::move(kv));
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return spec;
}

}  // namespace dabench
