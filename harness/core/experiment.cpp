#include "harness/core/experiment.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <utility>

#include <boost/program_options.hpp>
#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"

namespace dabench {

namespace po = boost::program_options;

std::vector<std::string> expand_sweep_values(const std::string& text) {
  std::vector<std::string> values;
  const std::string_view view = trim(text);
  if (view.find(':') != std::string_view::npos) {
    std::vector<double> parts;
    std::size_t start = 0;
    while (true) {
      const auto colon = view.find(':', start);
      double value = 0.0;
      if (!parse_double(view.substr(start, colon - start), value)) {
        throw InputError(fmt::format("range '{}' is not start:step:stop with numbers", text));
      }
      parts.push_back(value);
      if (colon == std::string_view::npos) break;
      start = colon + 1;
    }
    if (parts.size() != 3) throw InputError(fmt::format("range '{}' is not start:step:stop", text));
    const double first = parts[0], step = parts[1], last = parts[2];
    if (!(step > 0.0) || last < first) {
      throw InputError(fmt::format("range '{}' needs step > 0 and stop >= start", text));
    }
    const double count = std::floor((last - first) / step + 1e-9) + 1.0;
    if (count > 1e6) throw InputError(fmt::format("range '{}' has more than a million values", text));
    for (int k = 0; k < static_cast<int>(count); ++k) {
      // 12 significant digits remove the binary noise of first + k·step (0.30000000000000004).
      values.push_back(fmt::format("{:.12g}", first + k * step));
    }
    return values;
  }
  std::size_t start = 0;
  while (true) {
    const auto comma = view.find(',', start);
    const std::string_view item = trim(view.substr(start, comma - start));
    if (item.empty()) throw InputError(fmt::format("empty value in list '{}'", text));
    values.emplace_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return values;
}

namespace {

struct SweepBlock {
  std::vector<std::pair<std::string, std::vector<std::string>>> axes;  // in file order
  std::vector<std::pair<std::string, std::string>> ties;               // key ← other key
  std::vector<std::string> axis_keys;                                  // each axis' key, "sweep.NAME.key"
};

// A value twice in one axis is the same point twice: an error naming the key's line and both
// positions. (Run after the sweep's size is checked: an axis then has at most kMaxSweepPoints values.)
void check_distinct_values(const SweepBlock& block, const std::map<std::string, int>& line_of_key,
                           const std::string& path) {
  for (std::size_t a = 0; a < block.axes.size(); ++a) {
    const std::string& key = block.axis_keys[a];
    const std::vector<std::string>& values = block.axes[a].second;
    std::map<std::string_view, std::size_t> first_index;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const auto [it, inserted] = first_index.try_emplace(values[i], i);
      if (inserted) continue;
      const auto line = line_of_key.find(key);
      throw InputError(fmt::format("{}{}: '{}' sweeps the value {} twice (its values {} and {})", path,
                                   line == line_of_key.end() ? "" : fmt::format(":{}", line->second), key, values[i],
                                   it->second + 1, i + 1));
    }
  }
}

void set_value(std::vector<KeyValue>& settings, const std::string& key, const std::string& value) {
  for (KeyValue& kv : settings) {
    if (kv.key == key) {
      kv.value = value;
      return;
    }
  }
  settings.push_back({key, value});
}

std::string value_of(const std::vector<KeyValue>& settings, const std::string& key) {
  for (const KeyValue& kv : settings) {
    if (kv.key == key) return kv.value;
  }
  return {};
}

void expand_block(const SweepBlock& block, const std::vector<KeyValue>& fixed, const std::string& where,
                  std::vector<std::vector<KeyValue>>& points) {
  std::vector<std::size_t> index(block.axes.size(), 0);
  while (true) {
    std::vector<KeyValue> settings = fixed;
    for (std::size_t a = 0; a < block.axes.size(); ++a) {
      set_value(settings, block.axes[a].first, block.axes[a].second[index[a]]);
    }
    for (const auto& [key, source] : block.ties) {
      bool swept = false;
      for (const auto& axis : block.axes) swept = swept || axis.first == source;
      if (!swept) throw InputError(fmt::format("{}: '{} = @{}' names a parameter this block does not sweep", where, key, source));
      set_value(settings, key, value_of(settings, source));
    }
    points.push_back(std::move(settings));
    // Odometer increment, last axis fastest.
    int a = static_cast<int>(block.axes.size()) - 1;
    while (a >= 0 && ++index[a] == block.axes[a].second.size()) index[a--] = 0;
    if (a < 0) return;
  }
}

}  // namespace

namespace {

// Boost's parser names a bad line by its text only, and keeps the last of a repeated key or
// section without a word: scan the lines first, so that a bad line, a key set twice and a section
// opened twice are each one error with its line numbers. Returns the line of each key (as Boost
// names it: "section.key").
std::map<std::string, int> check_ini_lines(const std::string& path, const std::string& text) {
  std::map<std::string, int> line_of_key;
  std::map<std::string, int> line_of_section;
  std::string section;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const std::string_view content = trim(std::string_view(line).substr(0, line.find('#')));
    if (content.empty()) continue;
    if (content.find('=') == std::string_view::npos) {
      if (content.front() != '[' || content.back() != ']') {
        throw InputError(fmt::format("{}:{}: '{}' is not 'key = value' or a [section]", path, number, content));
      }
      section = std::string(trim(content.substr(1, content.size() - 2)));
      const auto [it, inserted] = line_of_section.try_emplace(section, number);
      if (!inserted) {
        throw InputError(fmt::format("{}:{}: section [{}] is opened again (first at line {})", path, number, section,
                                     it->second));
      }
      continue;
    }
    const std::string key = std::string(trim(content.substr(0, content.find('='))));
    const std::string full_key = section.empty() ? key : section + "." + key;
    const auto [it, inserted] = line_of_key.try_emplace(full_key, number);
    const bool repeatable = full_key == "algorithm" || full_key == "reference";  // one line per SPEC
    if (!inserted && !repeatable) {
      throw InputError(fmt::format("{}:{}: '{}' is set again (first at line {})", path, number, full_key, it->second));
    }
  }
  return line_of_key;
}

}  // namespace

Experiment load_experiment(const std::string& path) {
  return parse_experiment(path, read_input_file(path, "an experiment file", kMaxExperimentBytes));
}

Experiment parse_experiment(const std::string& path, std::string text) {
  Experiment experiment;
  experiment.path = path;
  // A UTF-8 byte order mark (which some Windows editors write) is not part of the first key.
  if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);
  experiment.text = std::move(text);
  experiment.name = std::filesystem::path(path).stem().string();

  const std::map<std::string, int> line_of_key = check_ini_lines(path, experiment.text);
  po::parsed_options parsed(nullptr);
  try {
    std::istringstream stream(experiment.text);
    parsed = po::parse_config_file(stream, po::options_description(), /*allow_unregistered=*/true);
  } catch (const po::error& error) {
    throw InputError(fmt::format("{}: {}", path, error.what()));
  }

  std::vector<KeyValue> fixed;
  std::vector<SweepBlock> blocks;
  std::map<std::string, std::size_t> block_of_section;
  bool seen_trials = false;
  for (const po::option& option : parsed.options) {
    const std::string& key = option.string_key;
    const std::string value = option.value.empty() ? std::string() : std::string(trim(option.value.front()));
    const auto bad = [&](std::string_view what) {
      return InputError(fmt::format("{}: '{} = {}': {}", path, key, value, what));
    };
    if (key.rfind("scenario.", 0) == 0) {
      set_value(fixed, key.substr(9), value);
      continue;
    }
    if (key.rfind("metrics.", 0) == 0) {
      set_value(experiment.metric_settings, key.substr(8), value);
      continue;
    }
    if (key.rfind("sweep.", 0) == 0) {
      const auto dot = key.rfind('.');
      const std::string section = key.substr(0, dot);
      const std::string param = key.substr(dot + 1);
      auto [it, inserted] = block_of_section.try_emplace(section, blocks.size());
      if (inserted) blocks.emplace_back();
      SweepBlock& block = blocks[it->second];
      if (!value.empty() && value.front() == '@') {
        block.ties.emplace_back(param, value.substr(1));
      } else {
        try {
          block.axes.emplace_back(param, expand_sweep_values(value));
        } catch (const InputError& error) {
          throw bad(error.what());
        }
        block.axis_keys.push_back(key);
      }
      continue;
    }
    if (key == "name") {
      experiment.name = value;
    } else if (key == "description") {
      experiment.description = value;
    } else if (key == "scenario") {
      experiment.scenario = value;
    } else if (key == "trials") {
      if (!parse_int64(value, experiment.trials) || experiment.trials < 1) throw bad("trials must be an integer >= 1");
      seen_trials = true;
    } else if (key == "seed") {
      std::int64_t seed = 0;
      if (!parse_int64(value, seed) || seed < 0) throw bad("seed must be a non-negative integer");
      experiment.seed = static_cast<std::uint64_t>(seed);
    } else if (key == "output") {
      experiment.output = value;
    } else if (key == "reference") {
      experiment.references.push_back(value);
    } else if (key == "algorithm") {
      experiment.algorithms.push_back(value);
    } else if (key == "iterations") {
      if (value == "true" || value == "1" || value == "yes") {
        experiment.record_iterations = true;
      } else if (value == "false" || value == "0" || value == "no") {
        experiment.record_iterations = false;
      } else {
        throw bad("iterations must be true or false");
      }
    } else if (key == "beliefs") {
      if (value == "true" || value == "1" || value == "yes") {
        experiment.record_beliefs = true;
      } else if (value == "false" || value == "0" || value == "no") {
        experiment.record_beliefs = false;
      } else {
        throw bad("beliefs must be true or false");
      }
    } else {
      throw InputError(fmt::format("{}: unknown key '{}' (known: name, description, scenario, trials, seed, "
                                   "output, reference, algorithm, iterations, beliefs, [scenario], [metrics], "
                                   "[sweep...])", path, key));
    }
  }
  if (experiment.scenario.empty()) throw InputError(fmt::format("{}: missing 'scenario = NAME'", path));
  if (!seen_trials) throw InputError(fmt::format("{}: missing 'trials = N'", path));
  if (experiment.algorithms.empty() && experiment.references.empty()) {
    throw InputError(fmt::format("{}: no 'algorithm = SPEC' line", path));
  }
  if (experiment.output.empty()) experiment.output = "results/" + experiment.name;

  double points = 0.0;  // the sweep's size before any point is made (a product can overflow)
  for (const SweepBlock& block : blocks) {
    double block_points = 1.0;
    for (const auto& axis : block.axes) block_points *= static_cast<double>(axis.second.size());
    points += block_points;
  }
  if (points > kMaxSweepPoints) {
    throw InputError(fmt::format("{}: the sweep has {:.3g} points, more than {:.0f}", path, points, kMaxSweepPoints));
  }
  for (const SweepBlock& block : blocks) {
    check_distinct_values(block, line_of_key, path);
    for (const auto& axis : block.axes) {
      bool known = false;
      for (const auto& key : experiment.swept_keys) known = known || key == axis.first;
      if (!known) experiment.swept_keys.push_back(axis.first);
    }
    expand_block(block, fixed, path, experiment.points);
  }
  if (blocks.empty()) experiment.points.push_back(fixed);
  return experiment;
}

}  // namespace dabench
