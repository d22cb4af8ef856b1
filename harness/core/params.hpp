#pragma once
// Typed parameters at the edge. Every option struct (algorithm or scenario) exposes its fields
// once, through bind(ParamList&); that single table serves parsing `key=value` text, printing
// defaults in `dabench list`, and writing parameter columns in CSV files. Strings exist only
// here: after parsing, algorithms see plain struct fields.
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "harness/core/errors.hpp"

namespace dabench {

struct KeyValue {
  std::string key;
  std::string value;
};

class ParamList {
 public:
  using Target = std::variant<int*, std::int64_t*, double*, bool*, std::string*>;
  struct Entry {
    std::string key;
    Target target;
    std::string doc;
    std::vector<std::string> choices;  // named values of an int field (add_choice), else empty
  };

  void add(std::string_view key, int& field, std::string_view doc) { push(key, &field, doc); }
  void add(std::string_view key, std::int64_t& field, std::string_view doc) { push(key, &field, doc); }
  void add(std::string_view key, double& field, std::string_view doc) { push(key, &field, doc); }
  void add(std::string_view key, bool& field, std::string_view doc) { push(key, &field, doc); }
  // Text, e.g. a file path; the value is taken as written (trimmed). Commas cannot appear in a
  // spec's value (they separate keys), so paths with commas are not expressible.
  void add(std::string_view key, std::string& field, std::string_view doc) { push(key, &field, doc); }
  // A named choice, e.g. solver=newton|lbfgs|pdca: `field` holds the index of the chosen name.
  void add_choice(std::string_view key, int& field, std::vector<std::string> names, std::string_view doc) {
    push(key, &field, doc);
    entries_.back().choices = std::move(names);
  }

  const std::vector<Entry>& entries() const { return entries_; }
  const Entry* find(std::string_view key) const;

  // Parses `value` into the field named `key`; `owner` names the algorithm or scenario in
  // error messages. Throws InputError for an unknown key or a malformed value.
  void assign(std::string_view key, std::string_view value, std::string_view owner) const;

  // The field's current value as text (shortest round-trip form for doubles).
  static std::string format(const Entry& entry);
  // "key (int, default 5): doc" lines for `dabench list`.
  std::string describe(std::string_view indent) const;
  std::string known_keys() const;

 private:
  template <class T>
  void push(std::string_view key, T* field, std::string_view doc) {
    entries_.push_back(Entry{std::string(key), Target{field}, std::string(doc), {}});
  }
  std::vector<Entry> entries_;
};

// Splits "name" or "name:key=value,key=value" into the name and its key/value pairs.
// Throws InputError on empty names, missing '=', empty keys or repeated keys.
struct Spec {
  std::string name;
  std::vector<KeyValue> settings;
};
Spec parse_spec(std::string_view text);

// Builds an option struct from key/value pairs: defaults from the struct, then each pair by
// ParamList::assign, then the struct's own validate() (empty string = valid).
template <class Options>
Options make_options(const std::vector<KeyValue>& settings, std::string_view owner) {
  Options options;
  ParamList params;
  options.bind(params);
  for (const KeyValue& kv : settings) params.assign(kv.key, kv.value, owner);
  if (std::string why = options.validate(); !why.empty()) {
    throw InputError(std::string(owner) + ": " + why);
  }
  return options;
}

template <class Options>
std::vector<ParamList::Entry> default_entries() {
  static Options defaults;
  ParamList params;
  defaults.bind(params);
  return params.entries();
}

// Strict number parsing for the edge (whole string, finite values only).
[[nodiscard]] bool parse_double(std::string_view text, double& out);
bool parse_int64(std::string_view text, std::int64_t& out);  // also accepts integral "1e6"

std::string_view trim(std::string_view text);

}  // namespace dabench
