#pragma once
// Fields shared by the rows every run kind writes (trials.csv, targets.csv, tracks.csv, ...).
#include <string>
#include <string_view>

#include "harness/core/solve_report.hpp"

namespace dabench {

// ',' then the value in its shortest round-trip form; ',' alone when it is NaN or infinite
// (an empty field means "missing").
void append_number(std::string& row, double value);

// A status reason on one CSV line (line breaks become spaces): --resume counts lines.
std::string one_line(std::string_view reason);

// The status column: "ok", the "failed:<reason>" a runner recorded, or "skipped:<reason>".
void append_status(std::string& row, const SolveReport& report);

}  // namespace dabench
