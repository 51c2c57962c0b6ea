// [[fluid.layers]] → per-node relaxation times (fluid/viscosity_layers.hpp). One density,
// so ν_layer/ν = μ_layer/μ and, with ν = (τ − ½)/3 (docs/model.md eq 1.6),
//   τ_layer = ½ + (τ − ½) μ_layer/μ
// (a layer of the fluid's own viscosity gets exactly the fluid's τ). Rectangles in
// lattice units: x/h, y/h; a node belongs when its centre (i + ½, j + ½) lies inside.
#include <string>

#include "scene/units_detail.hpp"

namespace erythro::scene::detail {

std::vector<fluid::ViscosityLayer> derive_layers(const Scene& s, const LatticeSetup& L) {
  std::vector<fluid::ViscosityLayer> out;
  if (s.fluid.layers.empty()) return out;
  if (!L.has_fluid)
    reject(s, "[[fluid.layers]] set the fluid's viscosity, but transport.coupling = \"none\" builds no fluid");
  if (!s.cells.empty() && s.membrane && s.membrane->interior_viscosity_cP)
    reject(s, "[[fluid.layers]] and membrane.interior_viscosity_cP both set the per-node viscosity: give one of them");
  const double h = s.domain.spacing_um, tau = L.collision.tau, tau_min = 0.5 + s.limits.min_tau_margin;
  for (std::size_t i = 0; i < s.fluid.layers.size(); ++i) {
    const ViscosityLayerSpec& spec = s.fluid.layers[i];
    const std::string key = "fluid.layers[" + std::to_string(i) + "].";
    const std::array<double, 2> x = spec.x_um.value_or(std::array<double, 2>{0.0, s.domain.size_um[0]});
    for (const auto& [range, name] : {std::pair{&spec.y_um, "y_um"}, std::pair{&x, "x_um"}})
      if (!((*range)[0] < (*range)[1]))
        reject(s, "key '" + key + name + "' = " + vec(*range) + " must be increasing (µm): [from, to]");
    fluid::ViscosityLayer layer{x[0] / h, x[1] / h, spec.y_um[0] / h, spec.y_um[1] / h, 0.0};
    layer.tau = 0.5 + (tau - 0.5) * (spec.viscosity_cP / s.fluid.viscosity_cP);
    if (fluid::covered_nodes(L.grid, layer) == 0)
      reject(s, "key '" + key + "y_um' = " + vec(spec.y_um) + (spec.x_um ? " with x_um = " + vec(x) : "") +
                    " µm contains no node centre (nodes at (i + 0.5) × " + num(h) + " µm): the layer has no effect");
    if (!(layer.tau >= tau_min))
      reject(s, "key '" + key + "viscosity_cP' = " + num(spec.viscosity_cP) + " gives τ = " + num(layer.tau) +
                    ", below " + num(tau_min) + " (0.5 + limits.min_tau_margin): raise time.tau or the viscosity");
    if (!(layer.tau <= s.limits.max_tau))
      reject(s, "key '" + key + "viscosity_cP' = " + num(spec.viscosity_cP) + " gives τ = " + num(layer.tau) +
                    ", above " + num(s.limits.max_tau) + " (limits.max_tau): lower time.tau or the viscosity");
    check_trt_tau_minus(s, L, layer.tau, key + "viscosity_cP = " + num(spec.viscosity_cP) + " cP");
    out.push_back(layer);
  }
  return out;
}

}  // namespace erythro::scene::detail
