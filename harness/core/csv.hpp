#pragma once
// Minimal RFC 4180 CSV: fields with a comma, quote or newline are quoted (algorithm SPECs
// contain commas); an empty field means "missing".
#include <string>
#include <string_view>
#include <vector>

namespace dabench {

void append_csv_field(std::string& line, std::string_view field);
// Splits one line (without its newline) into fields; false if a quote is left open.
[[nodiscard]] bool split_csv_line(std::string_view line, std::vector<std::string>& fields);

}  // namespace dabench
