#pragma once
// Write-to-temporary-then-rename: a reader never sees a half-written file, and a
// failed write never destroys the previous version nor leaves the temporary behind.
#include <string>

namespace erythro::io {

// Path of the temporary file used while `final_path` is being written:
// "<final_path>.partial-<PID>" (the PID tells a stale one from a live one, output_folder.hpp).
std::string temporary_path_for(const std::string& final_path);

// Renames the temporary into place (atomic on one file system). If that fails, the
// temporary is removed and OutputError thrown.
void commit_temporary(const std::string& final_path);

// Removes the temporary of `final_path`, if any; never throws (clean-up after an error).
void discard_temporary(const std::string& final_path) noexcept;

// Writes `text` to `path` atomically. Throws OutputError (and leaves no temporary).
void write_text_atomically(const std::string& path, const std::string& text);

// Throws OutputError unless `dir` exists (or can be created) and is writable.
void ensure_writable_directory(const std::string& dir);

}  // namespace erythro::io
