#pragma once
// What a problem kind is to the runner (single scan, multi-scan, tracking, track-before-detect,
// and any kind added later): its scenarios and algorithms, the checks of an experiment on it,
// its trials.csv columns and per-item files, its primary error and time columns, what meta.json
// adds, and its execution. One descriptor per built-in kind lives in harness/run/kinds/<kind>.cpp
// beside its execution (<kind>_execution.{hpp,cpp}, which writes the rows of those files); a
// program's own kind registers with DABENCH_REGISTER_PROBLEM_KIND (docs/extending.md, "Adding a kind"). The
// planner, the runner, merge, meta.json, compare's defaults, schedule, `dabench list` and the
// Python catalogue loop over problem_kinds() and switch on nothing.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/experiment.hpp"
#include "harness/core/params.hpp"
#include "harness/run/execution.hpp"

namespace dabench {

class JsonObject;
struct RunPlan;

// A per-item file beside trials.csv: its rows start with the point's prefix then `trial`, in
// item order, so --resume can trim it to the items trials.csv holds.
struct ItemFile {
  std::string name;    // e.g. "targets.csv"
  std::string header;  // with its newline
};

// Where trials.csv keeps a row's algorithm time: `column` × `to_seconds`, times the row's
// `count_column` where one is named (track-before-detect: step_time_us × n_steps × 1e-6).
struct AlgorithmTimeColumn {
  std::string_view column;
  double to_seconds = 1.0;
  std::string_view count_column = {};
};

// One algorithm or scenario of a kind's registries, as the catalogues show it.
struct CatalogueEntry {
  const std::string* name;
  const std::string* summary;
  const std::vector<ParamList::Entry>* params;  // with their defaults and meanings
};

class ProblemKind {
 public:
  virtual ~ProblemKind() = default;
  virtual std::string_view name() const = 0;            // "single-scan", in messages
  virtual std::string_view key() const = 0;             // "single_scan", the Python catalogue's kind
  virtual std::string_view algorithm_noun() const = 0;  // "single-scan algorithm", "tracker"

  // `dabench list`: the titles of the kind's sections and their entries (name, summary, each
  // parameter with its default and meaning).
  virtual std::string_view algorithms_title() const = 0;
  virtual std::string_view scenarios_title() const = 0;
  virtual void list_algorithms(std::string& out) const = 0;
  virtual void list_scenarios(std::string& out) const = 0;
  // The same as data (the Python package's dabench.algorithms() and dabench.scenarios()).
  virtual std::vector<CatalogueEntry> algorithm_entries() const = 0;
  virtual std::vector<CatalogueEntry> scenario_entries() const = 0;

  // Scenarios and algorithms (the kind's registries).
  virtual bool has_scenario(const std::string& scenario) const = 0;
  virtual std::string scenario_names() const = 0;  // comma-separated
  // Every parameter of `scenario` at `settings`, effective values; InputError for a bad one.
  virtual std::vector<KeyValue> resolve(const std::string& scenario, const std::vector<KeyValue>& settings) const = 0;
  virtual bool has_algorithm(const std::string& name) const = 0;
  virtual void check_algorithm(const std::string& spec) const = 0;  // InputError for a bad SPEC

  // What an experiment on the kind may say. shares_items: an item's algorithms share its draw
  // and the reference's marginals (single scan): `reference` lines, one work unit per item, run
  // in order; otherwise one unit per (item, algorithm), longest first, and no references.
  virtual bool shares_items() const { return false; }
  virtual bool records_iterations() const { return false; }  // `iterations = true`
  virtual bool records_beliefs() const { return false; }     // `beliefs = true`
  virtual bool has_metric_options() const { return false; }  // an experiment's [metrics] section
  virtual void check_metric_options(const std::vector<KeyValue>& settings) const { static_cast<void>(settings); }

  // The files: trials.csv's metric columns (after point, parameters, trial, seed, algorithm,
  // status), and the per-item files written before trials.csv, in the writer's order.
  virtual const std::vector<std::string>& metric_columns() const = 0;
  virtual std::vector<ItemFile> item_files(const std::string& point_columns, const Experiment& experiment) const {
    static_cast<void>(point_columns);
    static_cast<void>(experiment);
    return {};
  }
  // The kind's primary columns: its error (trials.csv's, e.g. max_error) and its algorithm time.
  // `dabench compare` compares both when no --metric is given; `dabench schedule` and
  // `run --costs-from` read the time as a unit's cost.
  virtual std::string_view error_column() const = 0;
  virtual AlgorithmTimeColumn time_column() const = 0;
  std::vector<std::string> compared_metrics() const {
    return {std::string(error_column()), std::string(time_column().column)};
  }
  virtual void add_meta(const Experiment& experiment, JsonObject& meta) const {
    static_cast<void>(experiment);
    static_cast<void>(meta);
  }

  // The run's work: the plan's scenarios created once per sweep point.
  virtual std::unique_ptr<RunExecution> make_execution(const RunPlan& plan) const = 0;
};

// Every kind: single scan, multi-scan, tracking, track-before-detect, then those registered.
const std::vector<const ProblemKind*>& problem_kinds();
// Adds a kind defined outside harness/run/kinds (a program's own, e.g. the example kind of
// tests/support/example_kind.cpp), before main(), by DABENCH_REGISTER_PROBLEM_KIND(KindClass).
// Its name and key must be new (a clash ends the program with a message), its scenario names too
// (kind_of_scenario throws std::logic_error on a name two kinds hold).
void register_problem_kind(const ProblemKind& kind);
// The kind whose registry holds `scenario`, or null.
const ProblemKind* kind_of_scenario(const std::string& scenario);
// The built-in kind of single-scan problems (the Python package draws them).
const ProblemKind& single_scan_kind();

template <class Kind>
struct ProblemKindRegistration {
  ProblemKindRegistration() {
    static const Kind kind;
    register_problem_kind(kind);
  }
};

}  // namespace dabench

// At namespace scope in the kind's own source file, after the class.
#define DABENCH_REGISTER_PROBLEM_KIND(Kind) \
  static const ::dabench::ProblemKindRegistration<Kind> dabench_problem_kind_registration_##Kind {}
