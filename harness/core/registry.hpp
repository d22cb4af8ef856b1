#pragma once
// Name → factory tables: the generic registry each problem kind instantiates for its algorithms
// and scenarios (harness/<kind>/registry.hpp), and the entry built from a class that provides
// `using Options = ...;` (a struct with bind() and validate()), `static constexpr
// std::string_view kName`, `kSummary`, and a constructor from Options.
// Registries are function-local statics, filled before main() by static objects of the
// algorithm and scenario libraries (linked whole, so the linker never drops them).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"

namespace dabench {

template <class Product>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Product>(const std::vector<KeyValue>&)>;
  using Resolver = std::function<std::vector<KeyValue>(const std::vector<KeyValue>&)>;
  struct Entry {
    std::string name;
    std::string summary;
    std::vector<ParamList::Entry> defaults;  // points into a static default Options object
    Factory create;      // validated settings → object; throws InputError
    Resolver resolve;    // settings → every parameter with its effective value, in bind order
  };

  void add(Entry entry) {
    const std::string name = entry.name;
    entries_.emplace(name, std::move(entry));
  }
  // For entries made at run time (the Python module's register()): replaces one of the same name.
  void replace(Entry entry) {
    const std::string name = entry.name;
    entries_.insert_or_assign(name, std::move(entry));
  }
  void remove(std::string_view name) { entries_.erase(std::string(name)); }
  const Entry* find(std::string_view name) const {
    const auto it = entries_.find(std::string(name));
    return it == entries_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, Entry>& entries() const { return entries_; }

  // The object a SPEC ("name" or "name:key=value,...") names, built with its settings; InputError
  // for an unknown name ("unknown <noun> 'name' (known: ...)"), an unknown key or a bad value.
  std::unique_ptr<Product> make(std::string_view spec_text, std::string_view noun) const {
    const Spec spec = parse_spec(spec_text);
    const Entry* entry = find(spec.name);
    if (entry == nullptr) {
      const std::string known = names();
      throw InputError(fmt::format("unknown {} '{}' (known: {})", noun, spec.name, known.empty() ? "none registered" : known));
    }
    return entry->create(spec.settings);
  }

  std::string names() const {
    std::string text;
    for (const auto& [name, entry] : entries_) text += (text.empty() ? "" : ", ") + name;
    return text;
  }

 private:
  std::map<std::string, Entry> entries_;
};

template <class Made, class Product>
typename Registry<Product>::Entry make_registry_entry() {
  using Options = typename Made::Options;
  return {std::string(Made::kName), std::string(Made::kSummary), default_entries<Options>(),
          [](const std::vector<KeyValue>& settings) -> std::unique_ptr<Product> {
            return std::make_unique<Made>(make_options<Options>(settings, Made::kName));
          },
          [](const std::vector<KeyValue>& settings) {
            Options options = make_options<Options>(settings, Made::kName);
            ParamList params;
            options.bind(params);
            std::vector<KeyValue> values;
            for (const auto& entry : params.entries()) values.push_back({entry.key, ParamList::format(entry)});
            return values;
          }};
}

}  // namespace dabench
