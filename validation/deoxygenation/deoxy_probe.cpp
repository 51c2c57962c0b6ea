// Exploration driver for the deoxygenation calibration (not a V&V case; docs/validation-
// deoxygenation.md, "Findings"): one 2D run at (h, Δt, M, representation), its misfit to
// the planar reference, and (optionally) its curve sampled at the reference times, for
// off-line analysis of the M-drift between lattice levels.
//   deoxy_probe h_um dt_at_0p2_us M {ray|frac} [out.csv]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/calibration.hpp"
#include "deoxy_run.hpp"

using namespace erythro;

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s h_um dt_at_0p2_us M {ray|frac} [out.csv]\n", argv[0]);
    return 2;
  }
  const auto ref = deoxy::read_reference(std::string(ERYTHRO_DEOXY_REFERENCE_DIR) + "/reference_S_planar.csv", 1);
  deoxy::Setup s;
  s.h_um = std::atof(argv[1]);
  s.dt_s = deoxy::diffusive_dt(s.h_um, std::atof(argv[2]) * 1e-6);
  s.hb.M = std::atof(argv[3]);
  s.representation = std::string(argv[4]) == "ray" ? deoxy::Representation::ray_cast
                                                   : deoxy::Representation::area_fraction;
  s.t_end_s = ref.t.back();
  const auto r = deoxy::run(s);
  const auto m = vv::curve_misfit(r.S, ref);
  std::printf("h %.4f dt_us %.4f M %.5f rep %s nodes %d heme_nodes %ld area %.5f polygon %.5f steps %ld max %.6f "
              "rms %.6f balance %.2e wall %.1f\n",
              s.h_um, s.dt_s * 1e6, s.hb.M, argv[4], r.nodes, r.interior_nodes, r.interior_area_um2,
              r.polygon_area_um2, r.steps, m.max_abs, m.rms, r.balance_residual, r.wall_s);
  if (argc > 5) {
    FILE* f = std::fopen(argv[5], "w");
    if (!f) return 1;
    std::fprintf(f, "t_s,S_sim,S_ref\n");
    for (std::size_t k = 0; k < ref.t.size(); ++k)
      std::fprintf(f, "%.9g,%.12g,%.12g\n", ref.t[k], vv::interpolate(r.S, ref.t[k]), ref.y[k]);
    std::fclose(f);
  }
  return 0;
}
