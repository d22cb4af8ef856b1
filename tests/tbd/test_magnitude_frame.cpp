// Tests of the frame file of the toy (scenarios/tbd/magnitude_frame.hpp): the supplement's
// Fig. 1(a), digitised in experiments/tbd/fig1a-frame.csv, read cell by cell; malformed
// files are one-line errors naming the file and line; the toy scenario with `frame` uses the
// file's frame and draws nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "harness/core/params.hpp"
#include "harness/tbd/registry.hpp"
#include "scenarios/tbd/magnitude_frame.hpp"
#include "scenarios/tbd/tbd.hpp"
#include "tests/support/input_error.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::read_magnitude_frame;

const std::string kFig1a = std::string(DABENCH_SOURCE_DIR) + "/experiments/tbd/fig1a-frame.csv";

// A file under the temporary folder holding `text`; removed with the object.
struct TextFile {
  std::filesystem::path path;
  explicit TextFile(const std::string& name, const std::string& text)
      : path(std::filesystem::temp_directory_path() / ("dabench-test-" + name)) {
    std::ofstream(path) << text;
  }
  ~TextFile() { std::filesystem::remove(path); }
};

std::string error_of(const std::string& path, int columns = 3, int rows = 2) {
  return dabench::test::input_error_message([&] { read_magnitude_frame(path, columns, rows, 1.0); });
}

}  // namespace

TEST_CASE("magnitude frame: the digitised Fig. 1(a) has the cells read off the figure, bottom row first",
          "[tbd][frame]") {
  const auto frame = read_magnitude_frame(kFig1a, 10, 10, 1.25);
  REQUIRE(frame.z.cols() == 100);
  CHECK(frame.unread_cells == 18);  // x 4..10, y 7..10: under the legend
  const auto at = [&](double x, double y) {  // the cell whose centre is (x, y)
    return frame.z.col(static_cast<int>(y - 0.5) * 10 + static_cast<int>(x - 0.5));
  };
  // The four cells around object 1 at (4, 4), each 0.71 m from it (docs/models/track-before-detect.md §1.2).
  CHECK(at(4.5, 4.5).x() == 12.3);  // shared with object 2 at (5, 5)
  CHECK(at(3.5, 3.5).x() == 6.1);
  CHECK(at(4.5, 3.5).x() == 6.2);
  CHECK(at(3.5, 4.5).x() == 0.8);
  CHECK(at(0.5, 0.5).x() == 1.2);
  CHECK(at(9.5, 0.5).x() == 0.6);
  CHECK(at(0.5, 9.5).x() == 1.3);
  CHECK(at(9.5, 9.5).x() == 1.25);  // unread
  CHECK(frame.z.row(1).cwiseAbs().maxCoeff() == 0.0);  // z_j = (|z_j|, 0)
}

TEST_CASE("magnitude frame: malformed files are one-line errors naming the file and line", "[tbd][frame]") {
  using Catch::Matchers::Contains;
  const TextFile good("frame-good.csv", "# comment\n1, 2, 3\n\n0,nan,4.5\n");
  const auto frame = read_magnitude_frame(good.path.string(), 3, 2, 7.0);
  CHECK(frame.z(0, 0) == 1.0);
  CHECK(frame.z(0, 4) == 7.0);
  CHECK(frame.z(0, 5) == 4.5);
  CHECK(frame.unread_cells == 1);

  const TextFile short_row("frame-short.csv", "1,2,3\n1,2\n");
  CHECK_THAT(error_of(short_row.path.string()), Contains(":2: 2 magnitudes, expected 3"));
  const TextFile long_row("frame-long.csv", "1,2,3,4\n1,2,3\n");
  CHECK_THAT(error_of(long_row.path.string()), Contains(":1: more than 3 magnitudes"));
  const TextFile extra_row("frame-extra.csv", "1,2,3\n1,2,3\n1,2,3\n");
  CHECK_THAT(error_of(extra_row.path.string()), Contains(":3: more than 2 rows"));
  const TextFile missing_row("frame-missing.csv", "1,2,3\n");
  CHECK_THAT(error_of(missing_row.path.string()), Contains("1 rows of cells, expected 2"));
  for (const char* bad : {"-1", "abc", "inf", "", "1e999"}) {
    const TextFile file("frame-bad.csv", std::string("1,") + bad + ",3\n1,2,3\n");
    INFO("value '" << bad << "'");
    CHECK_THAT(error_of(file.path.string()), Contains(":1: column 2:") && Contains("is not a magnitude"));
  }
  CHECK_THAT(error_of("/dev/zero"), Contains("/dev/zero: not a regular file"));
  CHECK_THAT(error_of(std::filesystem::temp_directory_path().string()), Contains("not a regular file"));
  CHECK_THAT(error_of("/nonexistent/frame.csv"), Contains("not a regular file"));
  const TextFile big("frame-big.csv", std::string((1 << 20) + 1, '1'));
  CHECK_THAT(error_of(big.path.string()), Contains("larger than"));
  for (const std::string& message : {error_of("/dev/zero"), error_of(short_row.path.string())}) {
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("magnitude frame: the toy with `frame` uses the file's frame for every trial and draws nothing",
          "[tbd][frame][scenario]") {
  const auto* entry = dabench::tbd_scenario_registry().find("tbd");
  REQUIRE(entry != nullptr);
  const auto scenario = entry->create({{"layout", "toy"}, {"frame", kFig1a}});
  const auto expected = read_magnitude_frame(kFig1a, 10, 10, std::sqrt(2.0 * std::numbers::ln2));
  for (std::uint32_t trial = 0; trial < 2; ++trial) {
    dabench::RandomStream rng(7, 0, trial);
    dabench::TbdSample sample;
    scenario->generate(rng, sample);
    REQUIRE(sample.problem.frames.size() == 1);
    CHECK(sample.problem.frames[0] == expected.z);
    REQUIRE(sample.problem.initial_objects.size() == 2);
    CHECK(sample.problem.initial_objects[0].mean.head<2>() == Eigen::Vector2d(4.0, 4.0));
    CHECK(sample.problem.initial_objects[1].mean.head<2>() == Eigen::Vector2d(5.0, 5.0));
    dabench::RandomStream fresh(7, 0, trial);
    CHECK(rng.uniform() == fresh.uniform());  // generate() drew nothing
  }
  const auto other = entry->create({{"layout", "toy"}, {"frame", kFig1a}, {"unread_magnitude", "3"}});
  dabench::RandomStream rng(7, 0, 0);
  dabench::TbdSample sample;
  other->generate(rng, sample);
  CHECK(sample.problem.frames[0](0, 99) == 3.0);
  CHECK_THAT(dabench::test::input_error_message([&] { entry->create({{"layout", "toy"}, {"frame", "/dev/zero"}}); }),
             Catch::Matchers::Contains("not a regular file"));
}

}  // namespace DABENCH_TEST_FILE
