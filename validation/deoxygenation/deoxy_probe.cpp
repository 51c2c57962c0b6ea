// Exploration driver for the deoxygenation calibration (not a V&V case; docs/validation-
// deoxygenation.md, "Findings"): one 2D run at (h, Δt, M, representation) — the scene
// validation/deoxygenation/deoxygenation.toml with overrides, run as `erythro run` runs it
// (deoxy_run.hpp; run.h5 kept in <results>/runs/deoxy_probe/) — its misfit to the planar
// reference, and (optionally) its curve sampled at the reference times, for off-line analysis
// of the M-drift between lattice levels (fixed-M curve changes projected on ∂S/∂ln M). Run it
// with ERYTHRO_SOURCE_DIR set to the source tree (and ERYTHRO_RESULTS_DIR where to write).
//   deoxy_probe h_um dt_at_0p2_us M {ray|frac|moment|msample} [out.csv|-] [key=value ...]
// keys (controlled probes; defaults are the case's Setup):
//   din=D, dout=D   O2 diffusivity inside / outside the cell (µm²/s): din=2800 removes the contrast
//   box=L           half-width of the held box (µm)
//   c0in=C          initial free O2 in the cell (µM; default α P0 = 130): c0in=20 removes the jump
//   trt=Λ           TRT collision with magic parameter Λ (default BGK)
//   shift=dx,dy     cell centre offset from the box centre, in units of h
//   corr=1          mean P from the source-offset-corrected C (transport eq T7)
//   interface=series|node_tensor|face_tensor   diffusivity at the membrane (deoxy::InterfaceRule;
//                   transport eqs T9–T11; the tensor rules need trt=)
//   geom=axi        the cell of revolution on the axisymmetric lattice (with ref=3d)
//   kin=local       local Hb kinetics (a saturation per heme node, eq H4)
//   markers=N       polygon resolution of the cell
//   coupling=explicit|implicit|outflow   (deoxy::Coupling)
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "common/calibration.hpp"
#include "deoxy_run.hpp"

using namespace erythro;

namespace {

bool apply(deoxy::Setup& s, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos) return false;
  const std::string k = kv.substr(0, eq), v = kv.substr(eq + 1);
  if (k == "din") s.D_in = std::atof(v.c_str());
  else if (k == "dout") s.D_out = std::atof(v.c_str());
  else if (k == "box") s.box_half_um = std::atof(v.c_str());
  else if (k == "c0in") s.C0_in_uM = std::atof(v.c_str());
  else if (k == "trt") s.collision = {transport::Collision::trt, std::atof(v.c_str())};
  else if (k == "shift") std::sscanf(v.c_str(), "%lf,%lf", &s.offset_x_h, &s.offset_y_h);
  else if (k == "corr") s.source_corrected_P = v != "0";
  else if (k == "interface")
    s.interface = v == "node_tensor"   ? deoxy::InterfaceRule::node_tensor
                  : v == "face_tensor" ? deoxy::InterfaceRule::face_tensor
                                       : deoxy::InterfaceRule::series;
  else if (k == "geom") s.geometry = v == "axi" ? deoxy::Geometry::axisymmetric : deoxy::Geometry::planar;
  else if (k == "kin") s.kinetics = v == "local" ? deoxy::Kinetics::local : deoxy::Kinetics::cell_mean;
  else if (k == "markers") s.markers = std::atoi(v.c_str());
  else if (k == "coupling")
    s.coupling = v == "explicit" ? deoxy::Coupling::explicit_lagged
                 : v == "outflow" ? deoxy::Coupling::cell_implicit_outflow
                                  : deoxy::Coupling::cell_implicit;
  else return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s h_um dt_at_0p2_us M {ray|frac|moment|msample} [out.csv|-] [key=value ...]\n", argv[0]);
    return 2;
  }
  deoxy::Setup s;
  s.h_um = std::atof(argv[1]);
  s.dt_s = deoxy::diffusive_dt(s.h_um, std::atof(argv[2]) * 1e-6);
  s.hb.M = std::atof(argv[3]);
  const std::string rep = argv[4];
  s.representation = rep == "ray"      ? deoxy::Representation::ray_cast
                     : rep == "moment" ? deoxy::Representation::area_fraction_moment
                     : rep == "msample" ? deoxy::Representation::area_fraction_moment_sampling
                                       : deoxy::Representation::area_fraction;
  // ref=planar (default; what the cases calibrate against) or ref=3d (the cell of revolution).
  bool cell_3d = false;
  for (int a = 6; a < argc; ++a) {
    if (std::strcmp(argv[a], "ref=3d") == 0 || std::strcmp(argv[a], "ref=planar") == 0) {
      cell_3d = std::strcmp(argv[a], "ref=3d") == 0;
    } else if (!apply(s, argv[a])) {
      std::fprintf(stderr, "unknown option %s\n", argv[a]);
      return 2;
    }
  }
  const auto ref = deoxy::read_reference(
      std::string(ERYTHRO_DEOXY_REFERENCE_DIR) + (cell_3d ? "/reference_S.csv" : "/reference_S_planar.csv"), 1);
  s.t_end_s = ref.t.back();
  const auto r = deoxy::run(s, "deoxy_probe", "probe", true);
  const auto m = vv::curve_misfit(r.S, ref);
  std::printf("h %.4f dt_us %.4f M %.5f rep %s coll %s din %g dout %g box %g nodes %d heme_nodes %ld area %.5f polygon %.5f "
              "steps %ld max %.6f rms %.6f balance %.2e wall %.1f\n",
              s.h_um, s.dt_s * 1e6, s.hb.M, argv[4],
              s.collision.kind == transport::Collision::trt ? ("trt" + std::to_string(s.collision.magic)).c_str() : "bgk",
              s.D_in, s.D_out, s.box_half_um, r.nodes, r.interior_nodes,
              r.interior_area_um2, r.polygon_area_um2, r.steps, m.max_abs, m.rms, r.balance_residual, r.wall_s);
  if (argc > 5 && std::strcmp(argv[5], "-") != 0) {
    FILE* f = std::fopen(argv[5], "w");
    if (!f) return 1;
    std::fprintf(f, "t_s,S_sim,S_ref\n");
    for (std::size_t k = 0; k < ref.t.size(); ++k)
      std::fprintf(f, "%.9g,%.12g,%.12g\n", ref.t[k], vv::interpolate(r.S, ref.t[k]), ref.y[k]);
    std::fclose(f);
  }
  return 0;
}
