// The V&V result record: verdict logic and the HDF5 layout the report reads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/h5.hpp"
#include "io/result_record.hpp"

using namespace erythro::io;

TEST(Metric, ComparisonKinds) {
  Metric m{"m", "", "", 2.05, 2.0, 0.1, Comparison::absolute, ""};
  EXPECT_TRUE(m.passed());
  m.value = 2.2;
  EXPECT_FALSE(m.passed());
  m.comparison = Comparison::relative;  // |2.2-2|/2 = 0.1
  m.tolerance = 0.11;
  EXPECT_TRUE(m.passed());
  m.comparison = Comparison::at_most;
  EXPECT_FALSE(m.passed());
  m.comparison = Comparison::at_least;
  EXPECT_TRUE(m.passed());
  m.value = std::nan("");
  EXPECT_FALSE(m.passed()) << "a NaN metric can never pass";
}

TEST(ResultRecord, EmptyRecordFails) {
  ResultRecord r("empty", "test");
  EXPECT_FALSE(r.passed()) << "a case with no metric checks nothing";
}

TEST(ResultRecord, WritesSchemaReadBack) {
  const auto dir = std::filesystem::temp_directory_path() / "erythro_record_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "case.h5").string();
  ResultRecord r("case", "fluid");
  r.set_requirement("req");
  r.set_reference("ref");
  r.set_parameter("tau", 0.8);
  r.set_parameter("model", std::string("bgk"));
  r.add_run({{"N", 16.0}, {"error", 1e-3}, {"model", std::string("bgk")}});
  r.add_run({{"N", 32.0}, {"error", 2.5e-4}, {"model", std::string("bgk")}});
  r.add_metric({"order", "observed order", "", 2.0, 2.0, 0.1, Comparison::absolute, "why"});
  ConvergenceSeries s;
  s.name = "bgk";
  s.h = {1.0 / 16, 1.0 / 32};
  s.error = {1e-3, 2.5e-4};
  s.local_orders = {2.0};
  r.add_convergence(s);
  r.write(path);

  auto file = h5::open_file_read(path);
  EXPECT_EQ(h5::read_attr_string(file.id(), "verdict"), "pass");
  EXPECT_EQ(h5::read_attr_string(file.id(), "case"), "case");
  auto runs = h5::open_group(file.id(), "runs");
  EXPECT_EQ(h5::read_dataset(runs.id(), "N"), (std::vector<double>{16, 32}));
  auto metric = h5::open_group(file.id(), "metrics/order");
  EXPECT_DOUBLE_EQ(h5::read_attr_double(metric.id(), "value"), 2.0);
  EXPECT_EQ(h5::read_attr_string(metric.id(), "verdict"), "pass");
  auto conv = h5::open_group(file.id(), "convergence/bgk");
  EXPECT_EQ(h5::read_dataset(conv.id(), "error").size(), 2u);
  // No temporary file is left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos);
  }
}
