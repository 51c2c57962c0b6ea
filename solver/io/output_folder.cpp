#include "io/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include "common/error.hpp"

namespace erythro::io {
namespace fs = std::filesystem;

namespace {

constexpr const char* kLockName = ".erythro.lock";

// The PID recorded in a lock file ("" if it cannot be read, e.g. written a moment later).
std::string recorded_pid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  return n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
}

void record_pid(int fd) {
  const std::string pid = std::to_string(::getpid());
  // Only for the message of a refused run: a failure here does not matter.
  if (::ftruncate(fd, 0) != 0) return;
  [[maybe_unused]] const ssize_t written = ::pwrite(fd, pid.data(), pid.size(), 0);
}

// The PID of a temporary's writer: "run.h5.partial-1234" → 1234; none for other files.
std::optional<pid_t> partial_writer(const fs::path& file) {
  const std::string name = file.filename().string();
  const std::string marker = ".partial-";
  const std::size_t at = name.rfind(marker);
  if (at == std::string::npos || at == 0) return std::nullopt;
  const std::string digits = name.substr(at + marker.size());
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return static_cast<pid_t>(std::stol(digits));
}

bool process_alive(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

}  // namespace

OutputFolderLock::OutputFolderLock(const std::string& dir) {
  const std::string path = (fs::path(dir) / kLockName).string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw OutputError("cannot create the lock file '" + path + "': " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string holder = recorded_pid(fd_);
    ::close(fd_);
    if (error != EWOULDBLOCK) throw OutputError("cannot lock the output folder '" + dir + "': " + std::strerror(error));
    throw OutputError("output folder '" + dir + "' is in use by another erythro run (PID " +
                      (holder.empty() ? std::string("unknown") : holder) +
                      "); wait for it to end or choose another folder with --out");
  }
  record_pid(fd_);
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

std::vector<std::string> remove_stale_partials(const std::string& dir, bool force) {
  std::vector<std::string> notes;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::optional<pid_t> writer = partial_writer(entry.path());
    if (!writer || !entry.is_regular_file(ec)) continue;
    const std::string name = entry.path().string();
    const bool alive = process_alive(*writer);
    if (alive && !force) {
      notes.push_back("kept '" + name + "': process " + std::to_string(*writer) +
                      " is still running (--force removes it)");
    } else if (fs::remove(entry.path(), ec)) {
      notes.push_back("removed '" + name + "' left by process " + std::to_string(*writer) +
                      (alive ? " (--force)" : ", which is no longer running"));
    } else {
      notes.push_back("cannot remove '" + name + "': " + ec.message());
    }
  }
  return notes;
}

}  // namespace erythro::io
