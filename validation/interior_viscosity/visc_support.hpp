#pragma once
// Shared pieces of the interior-viscosity cases (issue 5 items 1, 7–9;
// docs/validation-interior-viscosity.md): the thesis RBC-in-shear configuration
// with a given indicator method and viscosity ratio, the /runs row of one run, the
// shape and history plot series, and a one-line console summary.
#include <map>
#include <string>

#include "common/case_support.hpp"
#include "interior/index_field.hpp"
#include "io/result_record.hpp"
#include "rbc_run.hpp"

namespace erythro::vv {

// printf-style formatting of one number.

// Thesis Fig. II-3 set-up (thesis §II.4; docs/parameters.md): Evans–Fung RBC, a = 3.91 µm,
// plasma 1.2 cP, γ̇ = 100 1/s, thesis moduli, at lattice spacing h_um; cytoplasm
// μ_in = ratio·1.2 cP marked by `method` (indexless: one fluid).
RbcConfig thesis_config(double h_um, interior::Method method, double ratio, double strain);

// Set-up of the item-9 stability map (validation.rbc_viscosity_stability and
// validation.rbc_viscosity_long_runs): thesis_config with the flood-filled cytoplasm at
// ratio 5, τ_ex = tau_ex, E_S / ca_factor (Ca × ca_factor), and the lattice shear rate fixed
// at its τ_ex = 1, Re = 0.05 value (Re = 0.05·(1/6)/ν_ex), so the step count and the wall
// speed do not change with τ_ex; the membrane stability estimate is recorded, not enforced;
// the health monitor's edge-strain limit is 2 (the soft corner's segments stretch beyond 1).
RbcConfig stability_map_config(double h_um, double tau_ex, double ca_factor, double strain);

// "flood_fill x5 h=0.25" and the like.
std::string run_label(const RbcConfig& c);

// Parameters common to every interior-viscosity case (shape, moduli, walls, Re, ...).
void describe_setup(io::ResultRecord& rec, const RbcConfig& c, const RbcResult& r);

// One /runs row: method, ratio, h, τ_ex/τ_in, final D and θ, rates, regime, area and
// strain bounds, fill diagnostics, wall time, diverged + diagnosis.
std::map<std::string, io::Value> run_row(const RbcConfig& c, const RbcResult& r);

// Outline at the last snapshot (µm, about the centroid) and D, θ histories as series
// named "<prefix> shape", "<prefix> D", "<prefix> theta".
void add_run_series(io::ResultRecord& rec, const std::string& prefix, const RbcResult& r, bool histories);

// Final sample: D and θ (unwrapped, degrees) at the end of the run.
inline double final_D(const RbcResult& r) { return r.D_h.empty() ? 0.0 : r.D_h.back(); }
inline double final_theta(const RbcResult& r) { return r.theta_h.empty() ? 0.0 : r.theta_h.back(); }

void print_run(const RbcConfig& c, const RbcResult& r);

}  // namespace erythro::vv
