#include "doublet_record.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "aggregation/morse_units.hpp"
#include "doublet_outcome.hpp"
#include "doublet_scene.hpp"
#include "geometry/polygon.hpp"
#include "geometry/shapes.hpp"
#include "scene/units.hpp"

namespace erythro::vv {

void add_mapping(io::ResultRecord& rec, const DoubletShearConfig& c, const DoubletShearResult& r) {
  rec.set_parameter("h_um", c.h_m * 1e6);
  rec.set_parameter("a_over_h", r.a_lat);
  rec.set_parameter("lattice", std::to_string(r.nx) + " x " + std::to_string(r.ny) +
                                   fmt(" (%.0f x ", c.box_m * 1e6) + fmt("%.0f um), walls moving at -U/+U, periodic x", c.box_m * 1e6));
  rec.set_parameter("markers_per_cell", static_cast<double>(r.markers));
  rec.set_parameter("collision", fmt("BGK tau_ex = %.3g, ", c.tau) + fmt("tau_in = %.3g", r.tau_in));
  rec.set_parameter("interior", std::string(interior::to_string(c.indicator)) + fmt(", viscosity ratio %.3g", c.viscosity_ratio) +
                                    fmt(", index field every %.0f steps", c.index_update_interval));
  rec.set_parameter("kernel", "cosine4");
  rec.set_parameter("reynolds_lattice", c.reynolds);
  rec.set_parameter("reynolds_physical", r.reynolds_physical);
  rec.set_parameter("gamma_lattice", r.gamma_lat);
  rec.set_parameter("steps_per_strain_unit", 1.0 / r.gamma_lat);
  rec.set_parameter("bending_reduced_EB_over_a2Es", r.bending_reduced);
  rec.set_parameter("area_modulus", fmt("k_A = %.0f E_S/a", c.area_modulus));
  rec.set_parameter("morse_lattice", fmt("r0 = %.4g h, ", r.r0_lat) + fmt("beta = %.4g /h, ", r.beta_lat) +
                                         fmt("r_c = %.4g h, ", r.cutoff_lat) + fmt("flat-contact gap d* = %.4g h", r.flat_gap_lat));
  rec.set_parameter("morse_physical", fmt("r0 = %.3g um, ", c.r0_m * 1e6) + fmt("beta = %.3g /um, ", c.beta_per_m * 1e-6) +
                                          fmt("r_c = r0 + %.0f/beta", c.cutoff_k));
  if (c.de_star >= 0)
    rec.set_parameter("surface_energy_reading",
                      "levels and labels De* = k are the project's De* (docs/model.md eq 4.7, issue 21): gamma = k x "
                      "2.6e-8 J/m2, given as aggregation.surface_energy_J_m2; D_e = gamma / |J(d*)|; column "
                      "old_reading_de_star is gamma / E_S0 (the documented alternative reading)");
  else
    rec.set_parameter("surface_energy_reading",
                      "levels and labels De* = k are the old reading gamma = k E_S0 (docs/model.md eq 4.7, the documented "
                      "alternative), given as aggregation.surface_energy_J_m2; D_e = gamma / |J(d*)|; column de_star is "
                      "the project's De* = gamma / 2.6e-8 J/m2");
  rec.set_parameter("stability_max_dt_factor", r.stability_factor);
}

namespace {
void series(io::ResultRecord& rec, const std::string& name, const std::string& ylabel, const std::vector<double>& x,
            const std::vector<double>& y, const std::string& xlabel = "gamma t") {
  io::Series s;
  s.name = name;
  s.title = name;
  s.xlabel = xlabel;
  s.ylabel = ylabel;
  s.x = x;
  s.y = y;
  rec.add_series(s);
}
}  // namespace

void add_histories(io::ResultRecord& rec, const std::string& label, const DoubletShearResult& r) {
  const bool doublet = r.separation_h.empty() || r.separation_h.front() > 0;
  if (doublet) {
    series(rec, label + " theta", "tumbling angle theta (deg, line of centres, unwrapped)", r.strain_h, r.theta_h);
    series(rec, label + " contact area cell 0", "relative contact area, cell 0", r.strain_h, r.contact0_h);
    series(rec, label + " contact area cell 1", "relative contact area, cell 1", r.strain_h, r.contact1_h);
    series(rec, label + " separation", "separation of centres (um)", r.strain_h, r.separation_h);
    series(rec, label + " D cell 0", "Taylor deformation D, cell 0", r.strain_h, r.D0_h);
    series(rec, label + " D cell 1", "Taylor deformation D, cell 1", r.strain_h, r.D1_h);
    series(rec, label + " contact S amplitude", "S (odd cubic) amplitude of the contact line (um)", r.strain_h, r.sigmoid_h);
  } else {
    series(rec, label + " theta", "long-axis angle theta (deg, unwrapped)", r.strain_h, r.theta_h);
    series(rec, label + " axis ratio", "equivalent-ellipse axis ratio a/b", r.strain_h, r.aspect_h);
  }
  if (!r.snap_strain.empty()) {
    for (std::size_t k : {std::size_t{0}, r.snap_strain.size() - 1}) {
      series(rec, label + fmt(" outline gt=%.1f", r.snap_strain[k]), "y (um)", r.snap_x[k], r.snap_y[k], "x (um)");
      if (r.snap_strain.size() == 1) break;
    }
  }
}

void add_row(io::ResultRecord& rec, const std::string& label, const DoubletShearConfig& c, const DoubletShearResult& r) {
  const double Tq = quadrant_period(r);
  const double TJ = r.aspect_quadrant > 0 ? jeffery_period(r.aspect_quadrant) : -1;
  rec.add_run({{"run", label},
               {"shear_rate_1_s", c.shear_rate},
               {"old_reading_de_star", old_reading_level(c)},
               {"surface_energy_J_m2", surface_energy_J_m2(c)},
               {"de_star", aggregation::de_star_for_surface_energy(surface_energy_J_m2(c))},
               {"peak_adhesion_stress_Pa", r.peak_adhesion_stress_Pa},
               {"adhesion_to_viscous_stress", r.adhesion_to_viscous_stress},
               {"Es0_dyn_cm", c.Es0_N_m * 1e3},
               {"Es1_dyn_cm", c.Es1_N_m * 1e3},
               {"capillary0", r.capillary0},
               {"capillary1", r.capillary1},
               {"viscosity_ratio", c.viscosity_ratio},
               {"outcome", c.cells == 2 ? doublet_outcome(r) : std::string(r.t_theta_m90 >= 0 ? "tumbles" : "no tumble")},
               {"contact_mode", c.cells == 2 ? contact_mode(r) : std::string("-")},
               {"dissociation_strain", r.dissociation_strain},
               {"min_contact_after_gt1", r.min_contact_after1},
               {"max_S_um", max_sigmoid(r)},
               {"mean_contact_gt1", mean_contact(r, 1.0)},
               {"max_dD_cell0", max_deformation_change(r, 0)},
               {"max_dD_cell1", max_deformation_change(r, 1)},
               {"t_theta0", r.t_theta0},
               {"t_theta_m90", r.t_theta_m90},
               {"period_quadrant_gT", Tq},
               {"axis_ratio_quadrant", r.aspect_quadrant},
               {"jeffery_period_gT", TJ},
               {"period_over_jeffery", Tq > 0 && TJ > 0 ? Tq / TJ : -1.0},
               {"strain", r.strain},
               {"steps", static_cast<double>(r.steps)},
               {"max_area_change", r.max_area_change},
               {"max_edge_strain", r.max_edge_strain},
               {"max_edge_strain_cell0", r.max_edge_strain_cell[0]},
               {"max_edge_strain_cell1", r.max_edge_strain_cell[1]},
               {"wall_time_s", r.wall_time_s}},
              r.scene_text);
  for (const io::FieldPicture& p : r.pictures) rec.add_field(p);
}

void add_health_metrics(io::ResultRecord& rec, const std::string& label, const DoubletShearResult& r) {
  rec.add_metric({label + "_ran", "1 if the run ended without divergence (" + r.diagnosis + ")", "", r.diverged ? 0.0 : 1.0,
                  1.0, 0.0, io::Comparison::at_least, "a failed run cannot be classified"});
  rec.add_metric({label + "_max_area_change", "max over samples and cells of |A/A0 - 1|", "", r.max_area_change, 0.005,
                  0.0, io::Comparison::at_most,
                  "0.5 % as in validation.rbc_shear: the area penalty and the tension hold dA/A ~ 1e-3; a leak or a "
                  "failing membrane exceeds it"});
}

double max_marker_spacing_h(const DoubletShearConfig& c, const DoubletShearResult& r) {
  const double a = c.a_m / c.h_m;
  const geometry::Polygon rest = c.shape == CellShape::biconcave
                                     ? geometry::biconcave(c.markers, a)
                                     : geometry::ellipse(c.markers, a, a / c.ellipse_axis_ratio);
  double edge = 0;
  for (std::size_t m = 0; m < rest.size(); ++m) {
    const std::size_t n = (m + 1) % rest.size();
    edge = std::max(edge, std::hypot(rest.x[n] - rest.x[m], rest.y[n] - rest.y[m]));
  }
  return edge * (1.0 + r.max_edge_strain);
}

void add_marker_spacing_metric(io::ResultRecord& rec, const std::string& label, const DoubletShearConfig& c,
                               const DoubletShearResult& r) {
  rec.add_metric({label + "_max_marker_spacing",
                  "largest rest edge x (1 + max over samples, cells and edges of |l/l0 - 1|), in h", "h",
                  max_marker_spacing_h(c, r), scene::kMaxMarkerSpacing, 0.0, io::Comparison::at_most,
                  "membrane integrity: the IB kernel sees a closed membrane only while neighbouring markers are at "
                  "most h apart (the scene's default limits.max_marker_spacing; fluid leaks between markers further "
                  "apart); rest spacing 0.19 um = 0.64 h (study lattice), 0.39 h (CI lattice)"});
}

void print_run(const std::string& label, const DoubletShearResult& r) {
  std::printf("%s: %dx%d a/h=%.2f steps=%ld strain=%.2f wall=%.1fs outcome=%s mode=%s diss=%.2f minc=%.3f "
              "t0=%.2f t-90=%.2f t-180=%.2f Tq=%.2f r=%.3f TJ=%.2f dA=%.2e eps=%.3f Sm=%.3f %s\n",
              label.c_str(), r.nx, r.ny, r.a_lat, r.steps, r.strain, r.wall_time_s, doublet_outcome(r).c_str(),
              contact_mode(r).c_str(), r.dissociation_strain, r.min_contact_after1, r.t_theta0, r.t_theta_m90,
              r.t_theta_m180, quadrant_period(r), r.aspect_quadrant,
              r.aspect_quadrant > 0 ? jeffery_period(r.aspect_quadrant) : -1.0, r.max_area_change, r.max_edge_strain,
              max_sigmoid(r), r.diagnosis.c_str());
  for (std::size_t i = 0; i < r.strain_h.size(); i += 10)
    std::printf("  gt=%.2f th=%.1f c=%.3f/%.3f sep=%.3f gap=%.3f D=%.3f/%.3f S=%.3f B=%.3f ar=%.3f\n", r.strain_h[i],
                r.theta_h[i], r.contact0_h[i], r.contact1_h[i], r.separation_h[i], r.gap_h[i], r.D0_h[i], r.D1_h[i],
                r.sigmoid_h[i], r.bow_h[i], r.aspect_h[i]);
  std::fflush(stdout);
}

void finish_record(io::ResultRecord& rec, double wall_time_s) {
  rec.set_wall_time(wall_time_s);
  std::printf("written: %s (%.1f s)\n", rec.write_to_results_dir().c_str(), wall_time_s);
  for (const auto& m : rec.metrics()) EXPECT_TRUE(m.passed()) << m.name << " = " << m.value << " expected " << m.expected;
}

}  // namespace erythro::vv
