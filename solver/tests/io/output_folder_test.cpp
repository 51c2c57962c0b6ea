// The output folder of a run: one run at a time (the lock names its holder), and the
// temporary files of runs that are gone are removed, those of live ones kept.
#include "io/output_folder.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "common/error.hpp"

using namespace erythro;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const std::string& name) {
  auto dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void touch(const fs::path& path) { std::ofstream(path) << "x"; }

// The PID of a process that has ended (a child, reaped).
pid_t ended_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}
}  // namespace

TEST(OutputFolderLock, SecondLockFailsNamingFolderAndHolder) {
  const auto dir = fresh_dir("erythro_lock");
  std::optional<io::OutputFolderLock> first(std::in_place, dir.string());
  try {
    io::OutputFolderLock second(dir.string());  // another open file: flock conflicts even in one process
    FAIL() << "the second lock was granted";
  } catch (const OutputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'" + dir.string() + "' is in use"), std::string::npos) << message;
    EXPECT_NE(message.find("PID " + std::to_string(::getpid())), std::string::npos) << message;
  }
  first.reset();
  EXPECT_NO_THROW(io::OutputFolderLock again(dir.string()));  // released with its holder
}

TEST(RemoveStalePartials, RemovesThoseOfEndedProcessesOnly) {
  const auto dir = fresh_dir("erythro_stale");
  const std::string dead = std::to_string(ended_pid()), alive = std::to_string(::getpid());
  touch(dir / ("run.h5.partial-" + dead));
  touch(dir / ("run.xdmf.partial-" + dead));
  touch(dir / ("run.h5.partial-" + alive));
  touch(dir / "run.h5");
  touch(dir / "notes.partial-draft");  // not a temporary of erythro's: no PID

  const auto notes = io::remove_stale_partials(dir.string(), false);
  EXPECT_EQ(notes.size(), 3u);
  EXPECT_FALSE(fs::exists(dir / ("run.h5.partial-" + dead)));
  EXPECT_FALSE(fs::exists(dir / ("run.xdmf.partial-" + dead)));
  EXPECT_TRUE(fs::exists(dir / ("run.h5.partial-" + alive)));
  EXPECT_TRUE(fs::exists(dir / "run.h5"));
  EXPECT_TRUE(fs::exists(dir / "notes.partial-draft"));

  io::remove_stale_partials(dir.string(), true);  // --force: the live one too
  EXPECT_FALSE(fs::exists(dir / ("run.h5.partial-" + alive)));
  EXPECT_TRUE(fs::exists(dir / "run.h5"));
}
