#pragma once
// Write-to-temporary-then-rename: a reader never sees a half-written file, and a
// failed write never destroys the previous version.
#include <string>

namespace erythro::io {

// Path of the temporary file used while `final_path` is being written.
std::string temporary_path_for(const std::string& final_path);

// Renames the temporary into place (atomic on one file system).
void commit_temporary(const std::string& final_path);

// Writes `text` to `path` atomically.
void write_text_atomically(const std::string& path, const std::string& text);

// Throws OutputError unless `dir` exists (or can be created) and is writable.
void ensure_writable_directory(const std::string& dir);

}  // namespace erythro::io
