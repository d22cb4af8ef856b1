#include "harness/run/run_folder.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/json.hpp"
#include "harness/run/row_checksums.hpp"

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
RowItem parse_row_item(const RunPlan& plan, const std::string& path, std::string_view line, long long line_number,
                       std::vector<std::string>& fields) {
  const std::size_t trial_column = plan.point_params.front().size() + 1;
  RowItem item;
  if (!split_csv_line(line, fields) || fields.size() <= trial_column || !parse_int64(fields[0], item.point) ||
      !parse_int64(fields[trial_column], item.trial)) {
    throw InputError(fmt::format("{}:{}: malformed row; cannot resume (use --force to start over)", path, line_number));
  }
  return item;
}

[[noreturn]] void not_the_plans_row(const std::string& path, long long line_number, const std::string& found,
                                    const std::string& expected) {
  throw InputError(fmt::format("{}:{}: is {}, where this run has {}; cannot resume (use --force to start over)", path,
                               line_number, found, expected));
}

// Reads the rows of `path` after its header that checksums.csv records, calling on_row for each
// (InputError at the first row that is not the one written); a verification error gains the
// advice to start over.
VerifiedRows verified_rows(const RunPlan& plan, const std::string& path, std::size_t header_bytes,
                           const std::function<void(long long, std::string_view, std::uintmax_t)>& on_row) {
  try {
    RecordedChecksums recorded((fs::path(plan.output) / kChecksumsFile).string(), fs::path(path).filename().string());
    return verify_rows(path, header_bytes, recorded, on_row);
  } catch (const WriteError&) {
    throw;
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (message.find("--force") != std::string::npos) throw;
    throw InputError(message + "; cannot resume (use --force to start over)");
  }
}

// The kept part of a file being resumed: its first `rows` rows, `bytes` long with the header.
struct KeptRows {
  long long rows = 0;
  std::uintmax_t bytes = 0;
};

// trials.csv's whole items among its verified rows: row by row the plan's items in order (of a
// shard: its own), each with one row per SPEC in the plan's order.
KeptRows kept_trials(const RunPlan& plan, const std::string& path) {
  const auto rows_per_item = static_cast<long long>(plan.specs.size());
  const std::size_t spec_column = plan.point_params.front().size() + 3;  // point, params, trial, seed, algorithm
  const std::size_t header_bytes = plan.trials_header().size();
  std::vector<std::string> fields;
  KeptRows kept{0, header_bytes};
  verified_rows(plan, path, header_bytes, [&](long long row, std::string_view text, std::uintmax_t at) {
    const long long line_number = row + 2;
    if (row / rows_per_item >= plan.shard_items()) {
      throw InputError(fmt::format("{}:{}: more items than this run's {}; cannot resume (use --force to start over)",
                                   path, line_number, plan.shard_items()));
    }
    const RowItem found = parse_row_item(plan, path, text, line_number, fields);
    const long long global = plan.global_item(row / rows_per_item);
    const std::string& spec = plan.specs[static_cast<std::size_t>(row % rows_per_item)];
    const std::string found_spec = fields.size() > spec_column ? fields[spec_column] : std::string("no algorithm");
    if (found.point != global / plan.trials || found.trial != global % plan.trials || found_spec != spec) {
      not_the_plans_row(path, line_number, fmt::format("point {}, trial {}, {}", found.point, found.trial, found_spec),
                        fmt::format("point {}, trial {}, {}", global / plan.trials, global % plan.trials, spec));
    }
    if ((row + 1) % rows_per_item == 0) kept = KeptRows{row + 1, at + text.size() + 1};
  });
  return kept;
}

// A per-item file's rows of the first `items_done` items (of a shard: its own, numbered as in
// the plan) among its verified rows, which are in item order.
KeptRows kept_item_rows(const RunPlan& plan, const std::string& path, std::size_t header_bytes, long long items_done) {
  std::vector<std::string> fields;
  KeptRows kept{0, header_bytes};
  long long last = 0;
  bool done = false;
  verified_rows(plan, path, header_bytes, [&](long long row, std::string_view text, std::uintmax_t at) {
    if (done) return;
    const RowItem found = parse_row_item(plan, path, text, row + 2, fields);
    const bool in_plan = found.point >= 0 && found.point < static_cast<long long>(plan.point_params.size()) &&
                         found.trial >= 0 && found.trial < plan.trials;
    const long long local = in_plan ? plan.local_item(found.point * plan.trials + found.trial) : -1;
    if (local < last) {
      not_the_plans_row(path, row + 2, fmt::format("point {}, trial {}", found.point, found.trial),
                        fmt::format("its item {} or a later one", last));
    }
    if (local >= items_done) {
      done = true;
      return;
    }
    last = local;
    kept = KeptRows{row + 1, at + text.size() + 1};
  });
  return kept;
}

// The first `bytes` bytes of a file: its header, to compare with the plan's.
std::string read_prefix(const std::string& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string text(bytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(bytes));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return text;
}

void trim(const std::string& path, std::uintmax_t bytes) {
  std::error_code error;
  fs::resize_file(path, bytes, error);
  if (error) throw WriteError(fmt::format("{}: cannot trim to its verified rows ({})", path, error.message()));
}

// A new file, never written through: a symbolic link (or anything else) at `path` is removed
// first, so --force cannot write into whatever an old trials.csv pointed to.
std::FILE* create_with_header(const std::string& path, const std::string& header) {
  std::error_code error;
  fs::remove(path, error);
  std::FILE* file = open_or_throw(path, "wbx");
  if (std::fputs(header.c_str(), file) < 0 || std::fflush(file) != 0) {
    const int reason = errno;
    std::fclose(file);
    throw WriteError(fmt::format("{}: write failed ({})", path, std::strerror(reason)));
  }
  return file;
}

}  // namespace

const std::vector<std::string>& run_file_names() {
  static const std::vector<std::string> names = {"trials.csv",   "summary.csv",      "meta.json",      "checksums.csv",
                                                 "targets.csv",  "tracks.csv",       "measurements.csv", "iterations.csv",
                                                 "steps.csv",    "estimates.csv",    "frames.csv",     "beliefs.csv"};
  return names;
}

void remove_other_run_files(const RunPlan& plan) {
  const std::vector<std::string> own = plan.output_files();
  for (const std::string& name : run_file_names()) {
    if (std::find(own.begin(), own.end(), name) != own.end()) continue;
    std::error_code error;
    const fs::path path = fs::path(plan.output) / name;
    if (!fs::exists(fs::symlink_status(path, error))) continue;  // (a read-only folder refuses even that)
    fs::remove(path, error);
    if (error) throw WriteError(fmt::format("{}: cannot remove an earlier run's file ({})",
                                            (fs::path(plan.output) / name).string(), error.message()));
  }
}

OpenedRun open_run_files(const RunPlan& plan, bool resume, bool force, const std::string& initial_meta) {
  const std::string trials = trials_path(plan);
  const std::string meta = meta_path(plan);
  const bool holds_run = fs::exists(trials) || fs::exists(meta);
  if (holds_run && !resume && !force) {
    throw InputError(fmt::format("{}: already holds a run; use --resume to finish it or --force to start over",
                                 plan.output));
  }
  std::vector<ItemFile> files = plan.item_files();  // the writer's order: item files, then trials.csv
  files.push_back({"trials.csv", plan.trials_header()});
  OpenedRun opened;
  for (const ItemFile& file : files) opened.names.push_back(file.name);
  const auto path_of = [&plan](const std::string& name) { return (fs::path(plan.output) / name).string(); };
  const std::string header = plan.trials_header();
  if (resume && holds_run) {
    if (!fs::exists(meta)) {
      throw InputError(fmt::format("{}: cannot resume: meta.json is missing, so the run there cannot be checked to be "
                                   "this one (use --force to start over)", plan.output));
    }
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
    const std::string text = read_prefix(trials, header.size());
    if (text == header) {
      // Whole items of verified rows only: every item has one row per algorithm, and they must
      // be the plan's items in order; the item files keep those items' rows (written before
      // trials.csv's, so never fewer).
      std::vector<KeptRows> kept(files.size());  // an item file with no item kept: {0 rows, recreated}
      kept.back() = kept_trials(plan, trials);
      opened.items_done = kept.back().rows / static_cast<long long>(plan.specs.size());
      for (std::size_t k = 0; k + 1 < files.size() && opened.items_done > 0; ++k) {
        const std::string path = path_of(files[k].name);
        if (read_prefix(path, files[k].header.size()) != files[k].header) {
          throw InputError(fmt::format("{}: missing or its header differs from this experiment's; use --force to start over", path));
        }
        kept[k] = kept_item_rows(plan, path, files[k].header.size(), opened.items_done);
      }
      // checksums.csv first: a kill before the files are trimmed leaves rows it does not record.
      std::vector<std::size_t> header_bytes;
      std::vector<long long> rows;
      for (std::size_t k = 0; k < files.size(); ++k) {
        header_bytes.push_back(files[k].header.size());
        rows.push_back(kept[k].rows);
      }
      rewrite_checksums(plan.output, opened.names, header_bytes, rows);
      for (std::size_t k = 0; k < files.size(); ++k) {
        const std::string path = path_of(files[k].name);
        if (k + 1 < files.size() && opened.items_done == 0) {  // no rows to keep: its header may be cut
          opened.files.push_back(create_with_header(path, files[k].header));
          continue;
        }
        trim(path, kept[k].bytes);
        opened.files.push_back(open_or_throw(path, "ab"));
      }
      opened.files.push_back(open_or_throw(path_of(kChecksumsFile), "ab"));
      opened.resumed = true;
      return opened;
    }
    // A file cut inside its header (or never written) holds no rows: start it afresh.
    if (header.compare(0, text.size(), text) != 0) {
      throw InputError(fmt::format("{}: header differs from this experiment's; use --force to start over", trials));
    }
  }
  std::error_code error;
  fs::remove(fs::path(plan.output) / "summary.csv", error);
  remove_other_run_files(plan);
  // meta.json (with the run's fingerprint) exists before trials.csv, so any folder holding
  // rows can be checked by --resume; checksums.csv is started before the rows it records.
  write_file_atomically(meta, initial_meta);
  try {
    std::FILE* checksums = create_with_header(path_of(kChecksumsFile), kChecksumsHeader);
    opened.files.push_back(checksums);
    for (const ItemFile& file : files) opened.files.push_back(create_with_header(path_of(file.name), file.header));
  } catch (...) {
    for (std::FILE* file : opened.files) std::fclose(file);
    throw;
  }
  std::rotate(opened.files.begin(), opened.files.begin() + 1, opened.files.end());  // checksums.csv last
  return opened;
}

}  // namespace dabench
