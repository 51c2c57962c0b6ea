#pragma once
// Provenance of the binary, recorded in every output file.
#include <string>

namespace erythro::build_info {
std::string git_revision();  // `git describe --always --dirty` at build time
std::string compiler();      // compiler id and version
std::string compile_flags(); // build type and flags
std::string version();       // project version
}  // namespace erythro::build_info
