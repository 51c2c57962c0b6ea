#pragma once
// `erythro schema`: the key reference of docs/scenes.md, generated from the scene schema
// (scene/key_reference.hpp). Without options it prints the section; --write FILE puts it
// between the page's two marker lines; --check FILE exits 5 (exit_code::regression) naming
// the first line that differs when the page's section is stale. docs/cli.md.
#include <string>

namespace CLI {
class App;
}

namespace erythro::app {

struct SchemaOptions {
  std::string write_path;  // replace the section in this page
  std::string check_path;  // compare the section in this page
};

// Declares the `schema` subcommand on `cli`, filling `options`.
CLI::App* add_schema_subcommand(CLI::App& cli, SchemaOptions& options);
int schema_command(const SchemaOptions& options);

}  // namespace erythro::app
