#pragma once
// Reads the `--weights FILE` of `dabench solve`: a headerless numeric CSV matrix, by default
// one row per target, one column per measurement, entry ψ_i(j) ≥ 0 (eq 11; ψ_i(0) = 1 implied);
// other layouts and log weights as `--layout` and `--log` say (harness/single_scan/weights_layout.hpp).
#include <istream>
#include <string>

#include "harness/single_scan/problem.hpp"
#include "harness/single_scan/weights_layout.hpp"

namespace dabench {

// Throws InputError "FILE:LINE: problem" for an unreadable or empty file, a non-numeric entry,
// rows of different lengths, or what problem_from_weights refuses (a negative, NaN or infinite
// weight, a layout's side weight of 0, ...).
SingleScanProblem read_weights_csv(const std::string& path, const WeightsFormat& format = {});
// The same for text already open (`path` names it in messages).
SingleScanProblem parse_weights_csv(const std::string& path, std::istream& in, const WeightsFormat& format = {});

}  // namespace dabench
