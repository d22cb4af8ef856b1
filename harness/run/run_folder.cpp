#include "harness/run/run_folder.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
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

// Unbuffered: the ordered writer hands each block to the kernel in one fwrite, and a failed
// write leaves nothing behind in a stdio buffer that a later flush or fclose could append.
std::FILE* open_or_throw(const std::string& path, const char* mode) {
  std::FILE* file = std::fopen(path.c_str(), mode);
  if (file == nullptr) throw WriteError(fmt::format("{}: cannot open for writing ({})", path, std::strerror(errno)));
  std::setvbuf(file, nullptr, _IONBF, 0);
  return file;
}

// The fields of one kept row; throws unless it is whole CSV with a `point` and a `trial`.
struct RowItem {
  std::int64_t point = 0, trial = 0;
};
RowItem parse_row_item(const RunPlan& plan, const std::string& path, std::string_view line, std::size_t at,
                       std::vector<std::string>& fields) {
  const std::size_t trial_column = plan.point_params.front().size() + 1;
  RowItem item;
  if (!split_csv_line(line, fields) || fields.size() <= trial_column || !parse_int64(fields[0], item.point) ||
      !parse_int64(fields[trial_column], item.trial)) {
    throw InputError(fmt::format("{}: malformed row at byte {}; cannot resume (use --force to start over)", path, at));
  }
  return item;
}

[[noreturn]] void not_the_plans_row(const std::string& path, std::size_t at, const RowItem& found, const std::string& expected) {
  throw InputError(fmt::format("{}: the row at byte {} is point {}, trial {}, where this run has {}; cannot resume "
                               "(use --force to start over)", path, at, found.point, found.trial, expected));
}

// The kept rows of trials.csv (whole items, after the header) are, row by row, the plan's items
// in order (of a shard: its own), each with one row per SPEC in the plan's order.
void check_kept_trials(const RunPlan& plan, const std::string& path, std::string_view rows) {
  const std::size_t rows_per_item = plan.specs.size();
  const std::size_t spec_column = plan.point_params.front().size() + 3;  // point, params, trial, seed, algorithm
  const std::size_t offset = plan.trials_header().size();
  std::vector<std::string> fields;
  std::size_t row = 0;
  for (std::size_t at = 0; at < rows.size(); ++row) {
    const std::size_t end = rows.find('\n', at);
    const RowItem found = parse_row_item(plan, path, rows.substr(at, end - at), offset + at, fields);
    const long long global = plan.global_item(static_cast<long long>(row / rows_per_item));
    const std::string& spec = plan.specs[row % rows_per_item];
    if (found.point != global / plan.trials || found.trial != global % plan.trials || fields.size() <= spec_column ||
        fields[spec_column] != spec) {
      not_the_plans_row(path, offset + at, found,
                        fmt::format("point {}, trial {}, {}", global / plan.trials, global % plan.trials, spec));
    }
    at = end + 1;
  }
}

}  // namespace

const std::vector<std::string>& run_file_names() {
  static const std::vector<std::string> names = {"trials.csv",   "summary.csv",      "meta.json",      "targets.csv",
                                                 "tracks.csv",   "measurements.csv", "iterations.csv", "steps.csv",
                                                 "estimates.csv", "frames.csv",      "beliefs.csv"};
  return names;
}

void remove_other_run_files(const RunPlan& plan) {
  const std::vector<std::string> own = plan.output_files();
  for (const std::string& name : run_file_names()) {
    if (std::find(own.begin(), own.end(), name) != own.end()) continue;
    std::error_code error;
    fs::remove(fs::path(plan.output) / name, error);
    if (error) throw InputError(fmt::format("{}: cannot remove an earlier run's file ({})",
                                            (fs::path(plan.output) / name).string(), error.message()));
  }
}

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
      // Keep whole items only: every item has one row per algorithm, and they must be the
      // plan's items in order.
      const long long rows_per_item = static_cast<long long>(plan.specs.size());
      long long complete_lines = 0;
      std::size_t end_of_items = header.size();
      for (std::size_t at = header.size(); at < text.size(); ++at) {
        if (text[at] != '\n') continue;
        if (++complete_lines % rows_per_item == 0) end_of_items = at + 1;
      }
      if (complete_lines / rows_per_item > plan.shard_items()) {
        throw InputError(fmt::format("{}: holds {} items, more than this run's {}; cannot resume (use --force to start over)",
                                     trials, complete_lines / rows_per_item, plan.shard_items()));
      }
      opened.items_done = complete_lines / rows_per_item;
      check_kept_trials(plan, trials, std::string_view(text).substr(header.size(), end_of_items - header.size()));
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
  remove_other_run_files(plan);
  // meta.json (with the run's fingerprint) exists before trials.csv, so any folder holding
  // rows can be checked by --resume.
  write_file_atomically(meta, initial_meta);
  opened.file = open_or_throw(trials, "wb");
  if (std::fputs(header.c_str(), opened.file) < 0 || std::fflush(opened.file) != 0) {
    const int reason = errno;
    std::fclose(opened.file);
    throw WriteError(fmt::format("{}: write failed ({})", trials, std::strerror(reason)));
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
    // shard: its own, numbered as in the plan), and refuse rows of other items or out of order.
    std::vector<std::string> fields;
    std::size_t keep = header.size();
    long long last = 0;
    for (std::size_t at = header.size(); at < text.size();) {
      const auto end = text.find('\n', at);
      if (end == std::string::npos) break;
      const RowItem found = parse_row_item(plan, path, std::string_view(text).substr(at, end - at), at, fields);
      const long long local = found.point >= 0 && found.point < static_cast<long long>(plan.point_params.size()) &&
                                      found.trial >= 0 && found.trial < plan.trials
                                  ? plan.local_item(found.point * plan.trials + found.trial)
                                  : -1;
      if (local < last) not_the_plans_row(path, at, found, fmt::format("its item {} or a later one", last));
      if (local >= items_done) break;
      last = local;
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
    const int reason = errno;
    std::fclose(file);
    throw WriteError(fmt::format("{}: write failed ({})", path, std::strerror(reason)));
  }
  return file;
}

}  // namespace dabench
