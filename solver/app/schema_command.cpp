// `erythro schema` (schema_command.hpp): prints, writes or checks the generated key reference.
#include "app/schema_command.hpp"

#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <sstream>

#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "scene/key_reference.hpp"

namespace erythro::app {
namespace {

// The lines around the generated section of docs/scenes.md; each alone on its line.
const std::string kBegin = "<!-- BEGIN generated key reference (erythro schema --write docs/scenes.md) -->";
const std::string kEnd = "<!-- END generated key reference -->";

std::string read_page(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Offset of `marker` on a line of its own in `page`, from `from`; npos if absent.
std::size_t find_line(const std::string& page, const std::string& marker, std::size_t from = 0) {
  for (std::size_t at = page.find(marker, from); at != std::string::npos; at = page.find(marker, at + 1)) {
    const bool starts = at == 0 || page[at - 1] == '\n';
    const std::size_t after = at + marker.size();
    if (starts && (after == page.size() || page[after] == '\n')) return at;
  }
  return std::string::npos;
}

// The page with the text between the markers replaced by the current key reference.
std::string with_current_reference(const std::string& page, const std::string& path) {
  const std::size_t begin = find_line(page, kBegin);
  const std::size_t end = begin == std::string::npos ? begin : find_line(page, kEnd, begin);
  if (begin == std::string::npos || end == std::string::npos)
    throw InputError(path + ": no generated section: the page needs the line\n  " + kBegin +
                     "\nand after it the line\n  " + kEnd);
  return page.substr(0, begin) + kBegin + "\n\n" + scene::key_reference_markdown() + "\n" + page.substr(end);
}

// "FILE:LINE: ..." for the first line where `page` and `current` differ, or "" if none.
std::string first_difference(const std::string& page, const std::string& current, const std::string& path) {
  std::istringstream a(page), b(current);
  std::string found, expected;
  for (int line = 1;; ++line) {
    const bool more_found = static_cast<bool>(std::getline(a, found));
    const bool more_expected = static_cast<bool>(std::getline(b, expected));
    if (!more_found && !more_expected) return "";
    if (more_found && more_expected && found == expected) continue;
    return path + ":" + std::to_string(line) + ": the schema gives\n  " +
           (more_expected ? expected : "(end of page)") + "\nbut the page has\n  " +
           (more_found ? found : "(end of page)");
  }
}

}  // namespace

CLI::App* add_schema_subcommand(CLI::App& cli, SchemaOptions& options) {
  auto* cmd = cli.add_subcommand("schema", "Print the key reference of docs/scenes.md, generated from the schema");
  auto* write_option = cmd->add_option("--write", options.write_path, "Replace the generated section of this page");
  cmd->add_option("--check", options.check_path, "Exit 5 if the generated section of this page is stale")
      ->excludes(write_option);
  return cmd;
}

int schema_command(const SchemaOptions& options) {
  try {
    if (!options.write_path.empty()) {
      const std::string page = read_page(options.write_path);
      const std::string current = with_current_reference(page, options.write_path);
      if (current == page) {
        std::cout << options.write_path << ": the key reference is current\n";
        return exit_code::ok;
      }
      io::write_text_atomically(options.write_path, current);
      std::cout << options.write_path << ": wrote the key reference\n";
      return exit_code::ok;
    }
    if (!options.check_path.empty()) {
      const std::string page = read_page(options.check_path);
      const std::string difference = first_difference(page, with_current_reference(page, options.check_path),
                                                      options.check_path);
      if (difference.empty()) {
        std::cout << options.check_path << ": the key reference is current\n";
        return exit_code::ok;
      }
      std::cerr << "erythro: the key reference is stale: " << difference << "\n"
                << "erythro: regenerate it: erythro schema --write " << options.check_path << "\n";
      return exit_code::regression;
    }
    std::cout << scene::key_reference_markdown();
    return exit_code::ok;
  } catch (const InputError& e) {
    std::cerr << "erythro: error: " << e.what() << "\n";
    return exit_code::bad_input;
  } catch (const OutputError& e) {
    std::cerr << "erythro: error: " << e.what() << "\n";
    return exit_code::output_failure;
  } catch (const std::exception& e) {
    std::cerr << "erythro: error: internal error: " << e.what() << "\n";
    return exit_code::runtime_failure;
  }
}

}  // namespace erythro::app
