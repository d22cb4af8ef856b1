#pragma once
// Reads the `--weights FILE` of `dabench solve`: headerless numeric CSV, one row per target,
// one column per measurement, entry ψ_i(j) ≥ 0 (eq 11; ψ_i(0) = 1 implied).
#include <istream>
#include <string>

#include "harness/single_scan/problem.hpp"

namespace dabench {

// Throws InputError "FILE:LINE: problem" for an unreadable or empty file, a non-numeric,
// negative, NaN or infinite entry, or rows of different lengths.
SingleScanProblem read_weights_csv(const std::string& path);
// The same for text already open (`path` names it in messages).
SingleScanProblem parse_weights_csv(const std::string& path, std::istream& in);

}  // namespace dabench
