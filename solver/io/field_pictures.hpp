#pragma once
// Pictures of a run's last field output for the V&V report (docs/reports.md "Field
// pictures"): the speed |u| (with a fluid) and every species' concentration, each with
// the membranes of that step on top, in µm.
#include <string>
#include <vector>

#include "io/result_record.hpp"

namespace erythro::io {

// From run.h5 at `h5_path`; `label` starts each picture's name and title.
std::vector<FieldPicture> last_field_pictures(const std::string& h5_path, const std::string& label);

}  // namespace erythro::io
