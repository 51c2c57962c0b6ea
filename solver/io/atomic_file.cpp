#include "io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace erythro::io {

std::string temporary_path_for(const std::string& final_path) {
  return final_path + ".partial-" + std::to_string(::getpid());
}

void commit_temporary(const std::string& final_path) {
  std::error_code ec;
  std::filesystem::rename(temporary_path_for(final_path), final_path, ec);
  if (ec) {
    discard_temporary(final_path);
    throw OutputError("cannot move finished file into place at '" + final_path + "': " + ec.message());
  }
}

void discard_temporary(const std::string& final_path) noexcept {
  std::error_code ignored;
  std::filesystem::remove(temporary_path_for(final_path), ignored);
}

void write_text_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = temporary_path_for(path);
  std::ofstream out(tmp, std::ios::binary);
  out << text;
  out.close();  // the last bytes reach the disk here: a full disk may only show now
  if (!out) {
    const std::string reason = std::strerror(errno);
    discard_temporary(path);
    throw OutputError("cannot write '" + path + "': " + reason);
  }
  commit_temporary(path);
}

void ensure_writable_directory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create output folder '" + dir + "': " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw OutputError("output folder '" + dir + "' is not writable: " + std::strerror(errno));
  }
}

}  // namespace erythro::io
