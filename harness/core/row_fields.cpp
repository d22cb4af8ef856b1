#include "harness/core/row_fields.hpp"

#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "harness/core/csv.hpp"

namespace dabench {

void append_number(std::string& row, double value) {
  row += ',';
  if (std::isfinite(value)) fmt::format_to(std::back_inserter(row), "{}", value);
}

void append_status(std::string& row, const SolveReport& report) {
  if (report.skipped.empty()) {
    row += "ok";
  } else if (report.skipped.rfind("failed:", 0) == 0) {
    append_csv_field(row, report.skipped);
  } else {
    append_csv_field(row, "skipped:" + report.skipped);
  }
}

std::string one_line(std::string_view reason) {
  std::string line;
  for (const char c : reason) line += (c == '\n' || c == '\r') ? ' ' : c;
  return line;
}

}  // namespace dabench
