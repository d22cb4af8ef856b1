#include "scenarios/tbd/magnitude_frame.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"

namespace dabench {

namespace {

constexpr std::uintmax_t kMaxFrameBytes = std::uintmax_t{1} << 20;

}  // namespace

MagnitudeFrame read_magnitude_frame(const std::string& path, int columns, int rows, double unread) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(fmt::format("{}: not a regular file (a frame must be a table of cell magnitudes)", path));
  }
  if (std::filesystem::file_size(path, error) > kMaxFrameBytes) {
    throw InputError(fmt::format("{}: larger than {} bytes; a frame file is a small table", path, kMaxFrameBytes));
  }
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot read frame file", path));
  MagnitudeFrame frame;
  frame.z.setZero(2, static_cast<Eigen::Index>(columns) * rows);
  int row = 0;
  int line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    if (row == rows) throw InputError(fmt::format("{}:{}: more than {} rows of cells", path, line_number, rows));
    int column = 0;
    std::size_t start = 0;
    while (true) {
      const auto comma = text.find(',', start);
      const std::string_view field = trim(text.substr(start, comma == std::string_view::npos ? text.npos : comma - start));
      if (column == columns) {
        throw InputError(fmt::format("{}:{}: more than {} magnitudes in a row", path, line_number, columns));
      }
      double value = 0.0;
      if (field == "nan") {
        value = unread;
        ++frame.unread_cells;
      } else {
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
        if (field.empty() || ec != std::errc() || end != field.data() + field.size() || !std::isfinite(value) ||
            value < 0.0) {
          throw InputError(fmt::format("{}:{}: column {}: '{}' is not a magnitude (a finite number >= 0, or nan)",
                                       path, line_number, column + 1, field));
        }
      }
      frame.z(0, static_cast<Eigen::Index>(row) * columns + column) = value;
      ++column;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (column != columns) {
      throw InputError(fmt::format("{}:{}: {} magnitudes, expected {}", path, line_number, column, columns));
    }
    ++row;
  }
  if (row != rows) throw InputError(fmt::format("{}: {} rows of cells, expected {}", path, row, rows));
  return frame;
}

}  // namespace dabench
