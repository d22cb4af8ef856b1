#include "harness/run/shard_merge.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "harness/core/atomic_file.hpp"
#include "harness/core/csv.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/json.hpp"
#include "harness/core/params.hpp"
#include "harness/core/summary.hpp"
#include "harness/run/folder_lock.hpp"
#include "harness/run/row_checksums.hpp"
#include "harness/run/run_folder.hpp"
#include "harness/run/run_meta.hpp"
#include "harness/run/run_plan.hpp"
#include "harness/run/shard_meta.hpp"

namespace dabench {

namespace fs = std::filesystem;

namespace {

// The shards, checked to be one plan's 1..N each once, ordered by K.
std::vector<ShardMeta> read_shards(const std::vector<std::string>& paths) {
  if (paths.empty()) throw InputError("merge: no shard folders given");
  std::vector<ShardMeta> given;
  for (const std::string& path : paths) given.push_back(read_shard_meta(path));
  const ShardMeta& first = given.front();
  for (const ShardMeta& folder : given) {
    if (folder.field("fingerprint") != first.field("fingerprint")) {
      throw InputError(fmt::format("{}: a shard of another run plan (fingerprint {}, but {} has {})", folder.path,
                                   folder.field("fingerprint"), first.path, first.field("fingerprint")));
    }
    if (folder.field("seed") != first.field("seed")) {
      throw InputError(fmt::format("{}: a shard of another run (seed {}, but {} has {})", folder.path,
                                   folder.field("seed"), first.path, first.field("seed")));
    }
    if (folder.field("experiment") != first.field("experiment")) {
      throw InputError(fmt::format("{}: a shard of another run (its experiment text differs from {}'s)", folder.path,
                                   first.path));
    }
    if (folder.shard.count != first.shard.count) {
      throw InputError(fmt::format("{}: shard {} of a split into {}, but {} is shard {}", folder.path, folder.label,
                                   folder.shard.count, first.path, first.label));
    }
  }
  std::vector<const ShardMeta*> by_index(static_cast<std::size_t>(first.shard.count), nullptr);
  for (const ShardMeta& folder : given) {
    const ShardMeta*& slot = by_index[static_cast<std::size_t>(folder.shard.index - 1)];
    if (slot != nullptr) {
      throw InputError(fmt::format("shard {} given twice: {} and {}", folder.label, slot->path, folder.path));
    }
    slot = &folder;
  }
  std::string missing;  // the first few, so that the message stays one line
  constexpr int kListed = 8;
  int absent = 0;
  for (int k = 1; k <= first.shard.count; ++k) {
    if (by_index[static_cast<std::size_t>(k - 1)] != nullptr) continue;
    if (++absent <= kListed) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", k, first.shard.count);
  }
  if (absent > kListed) missing += fmt::format(" and {} more", absent - kListed);
  if (absent > 0) {
    throw InputError(fmt::format("shards missing: {} (given {} of {})", missing, given.size(), first.shard.count));
  }
  std::vector<ShardMeta> ordered;
  for (const ShardMeta* folder : by_index) ordered.push_back(*folder);
  return ordered;
}

// One shard's file, read row by row with each row's item (point · trials + trial), each row
// checked against the shard's checksums.csv (every row must be the one the shard wrote).
class ShardRows {
 public:
  ShardRows(const RunPlan& plan, const fs::path& path, const std::string& header)
      : plan_(plan), path_(path.string()), in_(checked(path)),
        recorded_((path.parent_path() / kChecksumsFile).string(), path.filename().string()) {
    std::string first;
    if (!in_ || !std::getline(in_, first) || first + "\n" != header) {
      throw InputError(fmt::format("{}: missing, or its header differs from the plan's", path_));
    }
    trial_column_ = plan.point_params.front().size() + 1;
    advance();
  }
  bool has_row() const { return has_row_; }
  // A shard's file is a regular file (its size is the run's: not bounded here).
  static const fs::path& checked(const fs::path& path) {
    check_input_file(path.string(), "a shard's result file", std::numeric_limits<std::uintmax_t>::max());
    return path;
  }
  long long item() const { return item_; }
  const std::string& row() const { return row_; }
  void advance() {
    has_row_ = static_cast<bool>(std::getline(in_, row_));
    const std::optional<std::uint32_t> expected = recorded_.next();
    if (!has_row_) {
      if (expected) {
        throw InputError(fmt::format("{}:{}: missing: the shard's checksums.csv records more rows than the file holds "
                                     "(rows deleted or the file cut)", path_, line_ + 1));
      }
      return;
    }
    ++line_;
    if (!expected || in_.eof() || row_checksum(row_) != *expected) {
      throw InputError(fmt::format("{}: not the row the shard wrote ({}: edited, cut short, or a row deleted before "
                                   "it)", where(), expected ? "its checksum differs from checksums.csv" : "checksums.csv records no such row"));
    }
    std::int64_t point = 0, trial = 0;
    if (!split_csv_line(row_, fields_) || fields_.size() <= trial_column_ || !parse_int64(fields_[0], point) ||
        !parse_int64(fields_[trial_column_], trial) || point < 0 ||
        point >= static_cast<std::int64_t>(plan_.point_params.size()) || trial < 0 || trial >= plan_.trials) {
      throw InputError(fmt::format("{}:{}: malformed row", path_, line_));
    }
    item_ = point * plan_.trials + trial;
  }
  std::string where() const { return fmt::format("{}:{}", path_, line_); }

 private:
  const RunPlan& plan_;
  std::string path_;
  std::ifstream in_;
  RecordedChecksums recorded_;
  std::size_t trial_column_ = 0;
  std::vector<std::string> fields_;
  std::string row_;
  bool has_row_ = false;
  long long item_ = -1, line_ = 1;
};

// Writes `name` of the merged run to `target` (and its rows' checksums to `checksums`): block b
// of the plan's items comes from shard b mod N, whose rows must be exactly its blocks' items in
// order (`rows_per_item` rows each when not 0). A failed write is a WriteError naming the file
// written and the system's reason (no shard is blamed for it).
void merge_file(const RunPlan& plan, const std::vector<ShardMeta>& shards, const std::string& name,
                const std::string& header, long long rows_per_item, const fs::path& target, std::FILE* checksums,
                const fs::path& checksums_path) {
  std::vector<ShardRows> readers;
  readers.reserve(shards.size());
  for (const ShardMeta& shard : shards) readers.emplace_back(plan, fs::path(shard.path) / name, header);
  std::FILE* out = std::fopen(target.c_str(), "wb");
  if (out == nullptr) throw WriteError(fmt::format("{}: cannot open for writing ({})", target.string(), std::strerror(errno)));
  ChecksumLineWriter checksum_lines(checksums, name);
  int reason = 0;  // errno of the first failed write; nothing more is written after it
  const auto put = [&](const char* text) {
    if (reason == 0 && std::fputs(text, out) < 0) reason = errno != 0 ? errno : EIO;
  };
  const auto failed = [&] {
    std::fclose(out);
    return WriteError(fmt::format("{}: write failed ({})", target.string(), std::strerror(reason)));
  };
  put(header.c_str());
  const auto shard_count = static_cast<long long>(shards.size());
  const long long blocks = (plan.items() + kItemsPerBlock - 1) / kItemsPerBlock;
  try {
    for (long long block = 0; block < blocks && reason == 0; ++block) {
      const auto s = static_cast<std::size_t>(block % shard_count);
      ShardRows& reader = readers[s];
      const long long begin = block * kItemsPerBlock, end = std::min(plan.items(), begin + kItemsPerBlock);
      std::array<long long, kItemsPerBlock> rows{};
      long long last = begin;
      while (reader.has_row() && reader.item() < end && reason == 0) {
        if (reader.item() < last) {
          throw InputError(fmt::format("{}: row of point {}, trial {} is not shard {}'s next item", reader.where(),
                                       reader.item() / plan.trials, reader.item() % plan.trials, shards[s].label));
        }
        last = reader.item();
        ++rows[static_cast<std::size_t>(reader.item() - begin)];
        put(reader.row().c_str());
        put("\n");
        checksum_lines.add(reader.row());
        reader.advance();
      }
      if (reason != 0) throw failed();
      for (long long item = begin; item < end && rows_per_item > 0; ++item) {
        if (rows[static_cast<std::size_t>(item - begin)] != rows_per_item) {
          throw InputError(fmt::format("{}/{}: point {}, trial {} has {} rows, not {}", shards[s].path, name,
                                       item / plan.trials, item % plan.trials, rows[static_cast<std::size_t>(item - begin)],
                                       rows_per_item));
        }
      }
    }
    if (reason != 0) throw failed();
    for (std::size_t s = 0; s < readers.size(); ++s) {
      if (readers[s].has_row()) {
        throw InputError(fmt::format("{}: row of point {}, trial {} is not shard {}'s", readers[s].where(),
                                     readers[s].item() / plan.trials, readers[s].item() % plan.trials, shards[s].label));
      }
    }
  } catch (const WriteError&) {
    throw;  // `out` is closed
  } catch (...) {
    std::fclose(out);
    throw;
  }
  if (std::fclose(out) != 0 && reason == 0) reason = errno;  // a buffered write may fail only here
  if (reason != 0) throw WriteError(fmt::format("{}: write failed ({})", target.string(), std::strerror(reason)));
  if (const int failure = checksum_lines.flush(); failure != 0) {
    throw WriteError(fmt::format("{}: write failed ({})", checksums_path.string(), std::strerror(failure)));
  }
}

// The shards' build, which must be one unless `allow_mixed` (then also each shard's, into
// `mixed` when they differ).
RecordedBuild shards_build(const std::vector<ShardMeta>& shards, bool allow_mixed, std::vector<RecordedBuild>& mixed) {
  std::vector<RecordedBuild> builds;
  for (const ShardMeta& shard : shards) {
    RecordedBuild build;
    build.version = shard.field("version");
    build.git_commit = shard.field("git_commit");
    build.source_modified = shard.field("source_modified");
    build.compiler = shard.field("compiler");
    build.flags = shard.field("flags");
    build.build_type = shard.field("build_type");
    if (!builds.empty() && build != builds.front() && !allow_mixed) {
      throw InputError(fmt::format("{}: shard {} was written by {}, but {} (shard {}) by {}; merge them with "
                                   "--allow-mixed (recorded in meta.json) or rerun one", shard.path, shard.label,
                                   build.describe(), shards.front().path, shards.front().label, builds.front().describe()));
    }
    builds.push_back(std::move(build));
  }
  if (std::any_of(builds.begin(), builds.end(), [&](const RecordedBuild& b) { return b != builds.front(); })) mixed = builds;
  return builds.front();
}

// meta.json's process fields of the merged run, from the shards'.
RunRecord merged_record(const std::vector<ShardMeta>& shards, const std::string& command_line, long long items) {
  RunRecord record;
  record.command_line = command_line;
  record.status = "complete";
  record.items_done = items;
  record.processes = static_cast<long long>(shards.size());
  std::set<std::string> seen_hosts;
  double busy = 0.0, capacity = 0.0;
  for (const ShardMeta& shard : shards) {
    const std::string start = shard.field("start_time"), end = shard.field("end_time"), host = shard.field("host");
    if (record.start_time.empty() || start < record.start_time) record.start_time = start;
    if (end > record.end_time) record.end_time = end;
    if (seen_hosts.insert(host).second) record.hosts += (record.hosts.empty() ? "" : ",") + host;
    record.resumed = record.resumed || shard.field("resumed") == "true";
    const double wall = shard.number("wall_seconds"), threads = shard.number("threads"), fraction = shard.number("work_fraction");
    if (std::isfinite(wall)) record.wall_seconds += wall;
    if (std::isfinite(wall) && std::isfinite(threads) && std::isfinite(fraction)) {
      busy += fraction * wall * threads;
      capacity += wall * threads;
    }
  }
  record.work_fraction = capacity > 0.0 ? busy / capacity : std::nan("");
  return record;
}

}  // namespace

MergeOutcome merge_shards(const MergeOptions& options) {
  const std::vector<ShardMeta> shards = read_shards(options.shards);
  for (const ShardMeta& shard : shards) {
    std::error_code error;
    if (fs::exists(options.output) && fs::equivalent(options.output, shard.path, error)) {
      throw InputError(fmt::format("{}: is shard {}; merge into another folder", options.output, shard.label));
    }
  }
  RunPlan plan = shard_run_plan(shards.front(), options.output);
  for (const ShardMeta& shard : shards) {
    plan.threads = std::max(plan.threads, shard.threads());
  }
  RunRecord record = merged_record(shards, options.command_line, plan.items());
  record.build = shards_build(shards, options.allow_mixed, record.mixed_builds);

  const bool created = !fs::exists(options.output);
  std::error_code error;
  std::optional<FolderLock> lock;
  // On an error, what this merge wrote goes: its temporary files, and the folder if it made it.
  std::vector<fs::path> temporaries;
  const auto clean_up = [&] {
    for (const fs::path& temporary : temporaries) fs::remove(temporary, error);
    if (lock) lock->release();
    if (created) fs::remove(options.output, error);
  };
  try {
    lock.emplace(options.output, "merge");  // held until the merged meta.json is written
    const bool holds_run = fs::exists(trials_path(plan)) || fs::exists(meta_path(plan));
    if (holds_run && !options.force) {
      throw InputError(fmt::format("{}: already holds a run; use --force to replace it", options.output));
    }
  } catch (...) {
    clean_up();
    throw;
  }
  std::vector<ItemFile> files = plan.item_files();
  files.push_back({"trials.csv", plan.trials_header()});
  files.push_back({kChecksumsFile, kChecksumsHeader});
  for (const ItemFile& file : files) temporaries.push_back(fs::path(options.output) / (file.name + ".merging"));
  try {
    const fs::path& checksums_path = temporaries.back();
    std::FILE* checksums = std::fopen(checksums_path.c_str(), "wb");
    if (checksums == nullptr || std::fputs(kChecksumsHeader, checksums) < 0) {
      const int reason = errno;
      if (checksums != nullptr) std::fclose(checksums);
      throw WriteError(fmt::format("{}: write failed ({})", checksums_path.string(), std::strerror(reason)));
    }
    try {
      for (std::size_t k = 0; k + 1 < files.size(); ++k) {
        merge_file(plan, shards, files[k].name, files[k].header,
                   files[k].name == "trials.csv" ? static_cast<long long>(plan.specs.size()) : 0, temporaries[k],
                   checksums, checksums_path);
      }
    } catch (...) {
      std::fclose(checksums);
      throw;
    }
    if (std::fclose(checksums) != 0) {
      throw WriteError(fmt::format("{}: write failed ({})", checksums_path.string(), std::strerror(errno)));
    }
    remove_other_run_files(plan);
    fs::remove(meta_path(plan), error);
    fs::remove(summary_path(plan), error);
    for (std::size_t k = 0; k < files.size(); ++k) {
      const fs::path target = fs::path(options.output) / files[k].name;
      fs::rename(temporaries[k], target, error);
      if (error) throw WriteError(fmt::format("{}: cannot replace file ({})", target.string(), error.message()));
    }
  } catch (...) {
    clean_up();
    throw;
  }
  write_summary(trials_path(plan), summary_path(plan), plan.metric_columns());
  write_file_atomically(meta_path(plan), run_meta_json(plan, record));

  MergeOutcome outcome;
  outcome.items = plan.items();
  outcome.shards = static_cast<int>(shards.size());
  for (const ItemFile& file : plan.item_files()) outcome.item_files.push_back(file.name);
  return outcome;
}

}  // namespace dabench
