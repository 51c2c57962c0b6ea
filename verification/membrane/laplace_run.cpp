#include "laplace_run.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/lattice_inputs.hpp"
#include "common/scene_case.hpp"
#include "geometry/polygon.hpp"
#include "lattice/d2q9.hpp"
#include "membrane_scene.hpp"

namespace erythro::vv {

LaplaceResult run_laplace(const LaplaceConfig& c, const std::string& case_name) {
  using namespace geometry;
  constexpr const char* kScene = "verification/membrane/inflated_circle.toml";
  const int L = static_cast<int>(std::lround(4 * c.radius));
  const int n = static_cast<int>(std::lround(8 * c.radius));
  // Centre off the lattice symmetry; marker 0 off the axes (0.01 rad). h = 1 µm.
  const double cx0 = 0.5 * L + 0.123, cy0 = 0.5 * L + 0.077;
  std::vector<std::string> set_up = {set("domain.size_um", double(L), double(L)), set("time.tau", c.tau)};
  const membrane::MembraneModel model{{membrane::TensionLawType::neo_hookean, c.modulus}, 0.0, 0.0};
  for (const std::string& o : membrane_overrides(kScene, set_up, c.kernel, model)) set_up.push_back(o);
  for (const std::string& o : {set("cells[0].radius_um", c.radius), set("cells[0].prestretch", c.stretch),
                               set("cells[0].center_um", cx0, cy0), angle_override("cells[0].angle_deg", 0.01),
                               set("cells[0].markers", long(n)),
                               // steady to ~1e-6 in dp (checked at R = 12)
                               set("run.steps", static_cast<long>(50 * c.radius * c.radius))})
    set_up.push_back(o);
  char label[64];
  std::snprintf(label, sizeof label, "%s_R%g", std::string(ib::to_string(c.kernel)).c_str(), c.radius);
  const CellRun run = run_cell_scene(case_scene(kScene, set_up), case_name, label, true);

  LaplaceResult r;
  r.scene_text = run.scene_text;
  r.diverged = run.diverged;
  r.steps = run.steps;
  r.wall_time_s = run.wall_time_s;
  if (r.diverged) return r;
  const Polygon& p = run.final;
  const double modulus = run.setup.membrane->model.tension.modulus;  // = c.modulus (exact input)
  double cx, cy;
  centroid(p, cx, cy);
  for (std::size_t i = 0; i < p.size(); ++i) r.radius += std::hypot(p.x[i] - cx, p.y[i] - cy);
  r.radius /= static_cast<double>(p.size());
  r.stretch = perimeter(p) / (2.0 * n * (c.radius / c.stretch) * std::sin(std::numbers::pi / n));
  r.tension = membrane::TensionLaw{membrane::TensionLawType::neo_hookean, modulus}.tension(r.stretch);
  r.dp_exact = r.tension / r.radius;
  r.polygon_term = std::sin(std::numbers::pi / n) / (std::numbers::pi / n) - 1.0;
  r.area_loss = 1.0 - signed_area(p) / signed_area(run.initial);
  // Pressure p = c_s² ρ: inside beyond the kernel reach (r < R − 3), outside far away (r > 1.5 R).
  const fluid::Moments& m = run.fields;
  double pin = 0, pout = 0;
  long nin = 0, nout = 0;
  for (int j = 0; j < L; ++j) {
    for (int i = 0; i < L; ++i) {
      double dx = i + 0.5 - cx, dy = j + 0.5 - cy;
      dx -= L * std::round(dx / L);
      dy -= L * std::round(dy / L);
      const double d = std::hypot(dx, dy);
      const std::size_t k = static_cast<std::size_t>(j) * L + i;
      const double pk = d2q9::cs2 * m.rho[k];
      if (d < r.radius - 3.0) { pin += pk; ++nin; }
      else if (d > 1.5 * r.radius) { pout += pk; ++nout; }
      r.max_fluid_speed = std::max(r.max_fluid_speed, std::hypot(m.ux[k], m.uy[k]));
    }
  }
  r.dp = pin / static_cast<double>(nin) - pout / static_cast<double>(nout);
  r.error = r.dp / r.dp_exact - 1.0;
  return r;
}

}  // namespace erythro::vv
