#pragma once
// Transport diagnostics at every sample, per species <name>:
//   <name>_mean_uM                    mean concentration over the nodes
//   <name>_mass_balance_residual      relative residual of the last transport step (docs/transport.md
//                                     eq T5; 0 at step 0)
//   <name>_max_mass_balance_residual  the largest |residual| after any transport step so far
//   <name>_amount_uM_um2              stored amount M(t) × h² (per unit depth; eq T5's M)
//   <name>_amount_change_uM_um2       (M(t) − M(0)) × h²
//   <name>_boundary_inflow_uM_um2     net amount that entered through the sides since the start × h²
//   <name>_change_uM                  max over the nodes of |C − C at the previous sample| (NaN at the
//                                     first): a [[stop_when]] below a tolerance ends a run at its
//                                     steady state
//   <name>_steady_balance             |inflow + net source| / |net source| of the last step (0 at a
//                                     steady state; 1 if nothing is produced or consumed but a net
//                                     amount flows in; 0 at step 0)
//   <name>_layer_<k>_top_flux_uM_um_s for each full-width [[transport.layers]] entry k of the species whose
//                                     top edge lies inside the domain: the flux across the lattice face nearest to
//                                     it (eq T6, +y), averaged over x, µM·µm/s
// and with [hemoglobin], per cell c: cell_c_saturation (the cell's HbO2 saturation; local kinetics: the mean
// over its heme volume) and cell_c_released_uM_um2 (O2 released since the start, C_heme (S0 − S) × heme
// area; axisymmetric: cell_c_released_uM_um3, × heme volume per radian).
#include <vector>

#include "simulation/probe.hpp"

namespace erythro::sim {

class TransportProbe : public Probe {
 public:
  explicit TransportProbe(const TransportPhysics& transport);
  void declare(std::vector<SeriesInfo>& series) const override;
  void sample(const ProbeContext& context, std::span<double> values) override;
  void register_stages(TimeLoop& loop) override;
  void save_state(StateRecord& record, const std::string& prefix) const override;
  void restore_state(const StateRecord& record, const std::string& prefix) override;

 private:
  struct LayerFlux {
    std::size_t species, row;  // face between row and row + 1
    int layer;
  };
  void track_residuals();
  const TransportPhysics& transport_;
  std::vector<double> worst_;                 // per species, max |residual| so far
  std::vector<std::vector<double>> previous_; // per species, C at the previous sample
  std::vector<LayerFlux> fluxes_;
  std::vector<double> east_, north_;          // face fluxes (scratch)
};

}  // namespace erythro::sim
