// libFuzzer target for the `erythro check` path (issue 17 part 7): a scene file's bytes go
// through the TOML parser, the --set overrides and derive_lattice, then the report and the
// resource estimate are formatted. Any bad input must end in an InputError; every other
// exception, a crash, or a sanitizer report is a bug. Built with -DERYTHRO_FUZZ=ON and clang
// (ci/fuzz.sh); the seed corpus is scenes/*.toml.
//
// Overrides ride along as TOML comments, so a seed is a plain scene file: each line
// "#--set KEY=VALUE" is passed as `--set KEY=VALUE`, after the file, as the command does.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "scene/resource_estimate.hpp"
#include "scene/scene_parser.hpp"
#include "scene/units.hpp"

namespace {

std::vector<std::string> overrides_in(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  const std::string marker = "#--set ";
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(marker, 0) == 0) out.push_back(line.substr(marker.size()));
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const erythro::scene::Scene scene = erythro::scene::parse_scene(text, "fuzz.toml", overrides_in(text));
    const erythro::scene::LatticeSetup setup = erythro::scene::derive_lattice(scene);
    const std::string report = erythro::scene::format_lattice_report(scene, setup) +
                               erythro::scene::format_resource_report(erythro::scene::estimate_resources(scene, setup));
    if (report.empty()) std::abort();  // keeps the formatting from being optimised away
  } catch (const erythro::InputError&) {
    // The expected end of a bad input.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}
