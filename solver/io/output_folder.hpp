#pragma once
// The output folder of one `erythro run`: used by one run at a time, and cleared of
// the temporary files a killed run left behind.
#include <string>
#include <vector>

namespace erythro::io {

// An exclusive lock on DIR/.erythro.lock (flock), held while the object lives, so that
// two runs into one folder cannot mix their files: the second fails at once. The kernel
// drops the lock when the process ends, however it ends (kill -9 included), so a dead
// run never blocks the next one. The file holds the holder's PID, for the message; it
// stays in the folder (deleting it would let a third run lock a different file).
class OutputFolderLock {
 public:
  // Throws OutputError naming the folder and the PID of the run that holds it.
  explicit OutputFolderLock(const std::string& dir);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Removes the temporary files ("<name>.partial-<PID>", atomic_file.hpp) that a killed run
// left in `dir`: those whose process is gone, and with `force` all of them. Call it with
// the folder's lock held. Returns one line per temporary found, saying what was done.
std::vector<std::string> remove_stale_partials(const std::string& dir, bool force);

}  // namespace erythro::io
