#include "bim_reference.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace erythro::vv {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  return cells;
}

}  // namespace

std::vector<BimReference> read_bim_reference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("capsule reference: cannot read " + path + " (reference_data/capsule_bim/capsule_bim.py)");
  std::string line;
  if (!std::getline(in, line)) throw InputError("capsule reference: " + path + " is empty");
  const std::vector<std::string> header = split_csv(line);
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw InputError("capsule reference: " + path + " has no column '" + name + "'");
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t law = column("law"), G = column("G"), D = column("D"), theta = column("theta_deg"),
                    T = column("T_gamma");
  std::vector<BimReference> rows;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = split_csv(line);
    if (cells.size() != header.size())
      throw InputError("capsule reference: " + path + " line " + std::to_string(line_number) + " has " +
                       std::to_string(cells.size()) + " cells, the header " + std::to_string(header.size()));
    try {
      rows.push_back({cells[law], std::stod(cells[G]), std::stod(cells[D]), std::stod(cells[theta]), std::stod(cells[T])});
    } catch (const std::logic_error&) {
      throw InputError("capsule reference: " + path + " line " + std::to_string(line_number) + " holds a non-number");
    }
  }
  if (rows.empty()) throw InputError("capsule reference: " + path + " has no rows");
  return rows;
}

}  // namespace erythro::vv
