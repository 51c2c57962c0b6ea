// Checkpoint files (io/checkpoint.hpp): the state comes back bit for bit (empty arrays,
// texts and special values included); a new checkpoint keeps the previous one, and a
// damaged newest file falls back to it.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/error.hpp"
#include "io/checkpoint.hpp"

using namespace erythro;

namespace {
std::filesystem::path fresh_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

StateRecord sample_state(double step) {
  StateRecord r;
  r.put_scalar("step", step);
  r.put("fluid.raw_populations", std::vector<double>{0.1, -0.0, std::numeric_limits<double>::quiet_NaN(), 1e-300});
  r.put("observation.stop_when_0.steps", std::vector<double>{});
  r.put_text("observation.stop_when_0.diagnosis", "stop_when[0]: step = 260 > 250");
  return r;
}
}  // namespace

TEST(Checkpoint, StateComesBackBitForBit) {
  const auto dir = fresh_dir("erythro_checkpoint_roundtrip");
  const StateRecord written = sample_state(7);
  io::write_checkpoint(dir.string(), "[scene]\nname = \"x\"\n", 7, written);
  const io::Checkpoint read = io::read_checkpoint(dir.string());
  EXPECT_EQ(read.step, 7);
  EXPECT_EQ(read.scene_text, "[scene]\nname = \"x\"\n");
  ASSERT_EQ(read.state.arrays().size(), written.arrays().size());
  for (const auto& [name, values] : written.arrays()) {
    const std::vector<double>& back = read.state.get(name);
    ASSERT_EQ(back.size(), values.size()) << name;
    for (std::size_t k = 0; k < values.size(); ++k)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(back[k]), std::bit_cast<std::uint64_t>(values[k])) << name << "[" << k << "]";
  }
  EXPECT_EQ(read.state.text("observation.stop_when_0.diagnosis"), "stop_when[0]: step = 260 > 250");
}

TEST(Checkpoint, RotationKeepsThePreviousAndFallsBackToIt) {
  const auto dir = fresh_dir("erythro_checkpoint_rotation");
  io::write_checkpoint(dir.string(), "a", 10, sample_state(10));
  io::write_checkpoint(dir.string(), "a", 20, sample_state(20));
  EXPECT_EQ(io::read_checkpoint(dir.string()).step, 20);
  EXPECT_TRUE(std::filesystem::exists(dir / io::kPreviousCheckpointName));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
  std::ofstream(dir / io::kCheckpointName, std::ios::trunc) << "not HDF5";  // a damaged newest file
  EXPECT_EQ(io::read_checkpoint(dir.string()).step, 10);
}

TEST(Checkpoint, NoCheckpointIsAnInputError) {
  const auto dir = fresh_dir("erythro_checkpoint_none");
  EXPECT_THROW(io::read_checkpoint(dir.string()), InputError);
}

TEST(StateRecord, MissingOrMisSizedEntriesNameTheEntry) {
  const StateRecord r = sample_state(1);
  try {
    r.get("cells.markers.x");
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cells.markers.x"), std::string::npos);
  }
  EXPECT_THROW(r.get("fluid.raw_populations", 3), InputError);
}
