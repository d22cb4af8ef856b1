#include "harness/run/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/json.hpp"

namespace dabench {

namespace fs = std::filesystem;

std::string trials_path(const RunPlan& plan) { return (fs::path(plan.output) / "trials.csv").string(); }
std::string summary_path(const RunPlan& plan) { return (fs::path(plan.output) / "summary.csv").string(); }
std::string meta_path(const RunPlan& plan) { return (fs::path(plan.output) / "meta.json").string(); }

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// What meta.json says the folder holds: the run's fingerprint and its shard ("" if absent).
std::string stored_fingerprint(const std::string& meta) { return json_value(meta, "fingerprint").value_or(""); }
std::string stored_shard(const std::string& meta) { return json_value(meta, "shard").value_or(""); }

std::FILE* open_or_throw(const std::string& path, const char* mode) {
  std::FILE* file = std::fopen(path.c_str(), mode);
  if (file == nullptr) throw InputError(fmt::format("{}: cannot open for writing", path));
  return file;
}

}  // namespace

OpenedTrials open_trials_file(const RunPlan& plan, bool resume, bool force, const std::string& initial_meta) {
  const std::string trials = trials_path(plan);
  const std::string meta = meta_path(plan);
  const bool holds_run = fs::exists(trials) || fs::exists(meta);
  if (holds_run && !resume && !force) {
    throw InputError(fmt::format("{}: already holds a run; use --resume to finish it or --force to start over",
                                 plan.output));
  }
  std::error_code error;
  fs::create_directories(plan.output, error);
  if (error) throw InputError(fmt::format("{}: cannot create output folder ({})", plan.output, error.message()));

  const std::string header = plan.trials_header();
  OpenedTrials opened;
  if (resume && holds_run) {
    const std::string stored = read_all(meta);
    if (stored_fingerprint(stored) != plan.fingerprint()) {
      throw InputError(fmt::format("{}: cannot resume: the run there used a different experiment, seed, trials or "
                                   "algorithms (use --force to start over)", plan.output));
    }
    if (stored_shard(stored) != plan.shard_label()) {
      const auto shard = [](const std::string& label) { return label.empty() ? std::string("no shard") : "shard " + label; };
      throw InputError(fmt::format("{}: cannot resume: the run there is {}, not {} (use --force to start over)",
                                   plan.output, shard(stored_shard(stored)), shard(plan.shard_label())));
    }
    const std::string text = read_all(trials);
    if (text.size() >= header.size() && text.compare(0, header.size(), header) == 0) {
      // Keep whole items only: every item has one row per algorithm.
      const long long rows_per_item = static_cast<long long>(plan.specs.size());
      long long complete_lines = 0;
      std::size_t end_of_items = header.size();
      for (std::size_t at = header.size(); at < text.size(); ++at) {
        if (text[at] != '\n') continue;
        if (++complete_lines % rows_per_item == 0) end_of_items = at + 1;
      }
      opened.items_done = std::min(complete_lines / rows_per_item, plan.shard_items());
      fs::resize_file(trials, end_of_items, error);
      if (error) throw InputError(fmt::format("{}: cannot trim partial rows ({})", trials, error.message()));
      opened.file = open_or_throw(trials, "ab");
      opened.resumed = true;
      return opened;
    }
    // A file cut inside its header (or never written) holds no rows: start it afresh.
    if (header.compare(0, text.size(), text) != 0) {
      throw InputError(fmt::format("{}: header differs from this experiment's; use --force to start over", trials));
    }
  }
  fs::remove(fs::path(plan.output) / "summary.csv", error);
  // meta.json (with the run's fingerprint) exists before trials.csv, so any folder holding
  // rows can be checked by --resume.
  write_file_atomically(meta, initial_meta);
  opened.file = open_or_throw(trials, "wb");
  if (std::fputs(header.c_str(), opened.file) < 0 || std::fflush(opened.file) != 0) {
    throw InputError(fmt::format("{}: write failed", trials));
  }
  return opened;
}

}  // namespace dabench

namespace dabench {

std::FILE* open_item_file(const RunPlan& plan, const ItemFile& item_file, long long items_done, bool resumed) {
  const std::string path = (fs::path(plan.output) / item_file.name).string();
  const std::string& header = item_file.header;
  if (resumed && items_done > 0) {
    const std::string text = read_all(path);
    if (text.compare(0, header.size(), header) != 0) {
      throw InputError(fmt::format("{}: missing or its header differs from this experiment's; use --force to start over", path));
    }
    // Rows are in item order; keep the complete lines of the first items_done items (of a
    // shard: those before its item items_done, in the plan's numbering).
    const long long first_not_done = items_done < plan.shard_items() ? plan.global_item(items_done) : plan.items();
    const std::size_t trial_column = plan.point_params.front().size() + 1;
    std::vector<std::string> fields;
    std::size_t keep = header.size();
    for (std::size_t at = header.size(); at < text.size();) {
      const auto end = text.find('\n', at);
      if (end == std::string::npos) break;
      std::int64_t point = 0, trial = 0;
      if (!split_csv_line(std::string_view(text).substr(at, end - at), fields) || fields.size() <= trial_column ||
          !parse_int64(fields[0], point) || !parse_int64(fields[trial_column], trial)) {
        throw InputError(fmt::format("{}: malformed row at byte {}; use --force to start over", path, at));
      }
      if (point * plan.trials + trial >= first_not_done) break;
      keep = end + 1;
      at = end + 1;
    }
    std::error_code error;
    fs::resize_file(path, keep, error);
    if (error) throw InputError(fmt::format("{}: cannot trim rows ({})", path, error.message()));
    return open_or_throw(path, "ab");
  }
  std::FILE* file = open_or_throw(path, "wb");
  if (std::fputs(header.c_str(), file) < 0 || std::fflush(file) != 0) {
    std::fclose(file);
    throw InputError(fmt::format("{}: write failed", path));
  }
  return file;
}

}  // namespace dabench
