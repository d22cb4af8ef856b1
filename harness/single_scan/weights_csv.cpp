#include "harness/single_scan/weights_csv.hpp"

#include <charconv>
#include <fstream>
#include <vector>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/input_file.hpp"
#include "harness/core/params.hpp"

namespace dabench {

SingleScanProblem read_weights_csv(const std::string& path, const WeightsFormat& format) {
  check_input_file(path, "a weights file", kMaxWeightsBytes);
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read weights file", path));
  return parse_weights_csv(path, in, format);
}

SingleScanProblem parse_weights_csv(const std::string& path, std::istream& in, const WeightsFormat& format) {
  std::vector<double> values;
  long long columns = -1;
  long long rows = 0;
  long long line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view text = trim(line);
    if (text.empty()) {
      // Blank lines are allowed only at the end of the file.
      std::string rest;
      while (std::getline(in, rest)) {
        ++line_number;
        if (!trim(rest).empty()) throw InputError(fmt::format("{}:{}: blank line inside the matrix", path, line_number - 1));
      }
      break;
    }
    long long count = 0;
    std::size_t start = 0;
    while (true) {
      const auto comma = text.find(',', start);
      const std::string_view field = trim(text.substr(start, comma == std::string_view::npos ? text.npos : comma - start));
      ++count;
      double value = 0.0;
      const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (field.empty() || ec != std::errc() || end != field.data() + field.size()) {
        throw InputError(fmt::format("{}:{}: column {}: '{}' is not a number", path, line_number, count, field));
      }
      values.push_back(value);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (columns >= 0 && count != columns) {
      throw InputError(fmt::format("{}:{}: {} columns, but line 1 has {} (ragged matrix)", path, line_number, count, columns));
    }
    columns = count;
    ++rows;
  }
  if (rows == 0) throw InputError(fmt::format("{}: empty weights file (expected one row per target)", path));
  return problem_from_weights(Eigen::Map<const RowMatrix>(values.data(), rows, columns), format, path);
}

}  // namespace dabench
