// The regression comparer: identical files pass, a moved quantity fails and is named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/baseline_compare.hpp"
#include "io/h5.hpp"

using namespace erythro::io;

namespace {
std::string write_file(const std::string& name, double value) {
  const auto path = std::filesystem::temp_directory_path() / name;
  auto file = h5::create_file(path.string());
  auto g = h5::create_group(file.id(), "fields");
  h5::write_dataset(g.id(), "velocity", std::vector<double>{1.0, 2.0, value});
  h5::write_dataset(file.id(), "mass", std::vector<double>{10.0});
  return path.string();
}
std::string write_tolerances() {
  const auto path = std::filesystem::temp_directory_path() / "erythro_tol.toml";
  std::ofstream(path) << "[default]\natol = 0.0\nrtol = 1e-12\n[quantity.velocity]\natol = 1e-6\nrtol = 0.0\n";
  return path.string();
}
}  // namespace

TEST(BaselineCompare, IdenticalPasses) {
  const auto a = write_file("erythro_a.h5", 3.0);
  const auto report = compare_to_baseline(a, a, write_tolerances());
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_EQ(report.datasets.size(), 2u);
}

TEST(BaselineCompare, WithinToleranceAndMoved) {
  const auto base = write_file("erythro_base.h5", 3.0);
  const auto near = write_file("erythro_near.h5", 3.0 + 5e-7);
  EXPECT_TRUE(compare_to_baseline(near, base, write_tolerances()).passed());
  const auto far = write_file("erythro_far.h5", 3.1);
  const auto report = compare_to_baseline(far, base, write_tolerances());
  EXPECT_FALSE(report.passed());
  const std::string text = report.to_text();
  EXPECT_NE(text.find("MOVED /fields/velocity"), std::string::npos) << text;
  EXPECT_NE(text.find("baseline 3 -> current 3.1"), std::string::npos) << text;
}

TEST(BaselineCompare, MissingDatasetFails) {
  const auto base = write_file("erythro_base2.h5", 3.0);
  const auto path = std::filesystem::temp_directory_path() / "erythro_empty.h5";
  { auto file = h5::create_file(path.string()); }
  EXPECT_FALSE(compare_to_baseline(path.string(), base, write_tolerances()).passed());
}
