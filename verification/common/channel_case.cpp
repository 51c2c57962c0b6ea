#include "common/channel_case.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "analysis/profiles.hpp"
#include "common/case_support.hpp"
#include "common/scene_case.hpp"
#include "scene/units.hpp"

namespace erythro::vv {

std::vector<std::string> channel_overrides(const ChannelRunSpec& spec, const std::vector<std::string>& extra) {
  const double mu = case_scene(spec.scene).fluid.viscosity_cP * 1e-3;
  const double force = 2.0 * mu * spec.wall_shear_rate_per_s / (spec.height_um * 1e-6);  // N/m³
  std::vector<std::string> o = extra;
  for (const std::string& s : {set("domain.size_um", spec.length_um, spec.height_um),
                               set("domain.spacing_um", spec.spacing_um), set("cell_populations[0].markers", spec.markers),
                               set("cell_populations[0].min_gap_um", spec.min_gap_um > 0.0 ? spec.min_gap_um : spec.spacing_um),
                               set("cell_populations[0].seed", spec.seed), set("body_force.density_N_m3", force, 0.0),
                               set("run.duration_s", spec.strain / spec.wall_shear_rate_per_s),
                               set("output.fields_interval_steps", 0L)})
    o.push_back(s);
  if (spec.checkpoint_interval_s > 0.0) o.push_back(set("output.checkpoint_interval_s", spec.checkpoint_interval_s));
  const double dt = scene::derive_lattice(case_scene(spec.scene, o)).scales.time_s;
  o.push_back(set("output.diagnostics_interval_steps",
                  std::max(1L, std::lround(spec.sample_strain / (spec.wall_shear_rate_per_s * dt)))));
  return o;
}

ChannelSeries run_channel(const ChannelRunSpec& spec, const std::string& case_name, const std::string& label,
                          const std::vector<std::string>& extra) {
  CaseRunOptions options;
  options.resume = spec.checkpoint_interval_s > 0.0;
  const CaseRun r = run_case_scene(case_scene(spec.scene, channel_overrides(spec, extra)), case_name, label, options);
  ChannelSeries out;
  out.resumable = options.resume;
  out.read_back = r.read_back;
  out.resumed_from_step = r.resumed_from_step;
  if (options.resume) std::printf("%s: %s\n", label.c_str(), r.resume_note.c_str());
  out.completed = r.ok();
  out.diagnosis = r.summary.diagnosis;
  for (double t : r.file.series("time_s")) out.strain.push_back(spec.wall_shear_rate_per_s * t);
  out.eta = r.file.series("relative_apparent_viscosity");
  out.cfl = r.file.series("cell_free_layer_normalised");
  out.hd = r.file.series("discharge_haematocrit");
  out.max_area_change = r.file.series("cells_max_area_change").back();
  out.max_edge_strain = r.file.series("cells_max_edge_strain").back();
  out.cells = static_cast<long>(r.setup.membrane->cells.size());
  out.steps = r.setup.total_steps;
  out.wall_s = r.wall_time_s;
  out.scene_text = r.file.scene_text();
  if (spec.settled_strain >= 0.0 && out.completed) {
    const double settled_s = spec.settled_strain / spec.wall_shear_rate_per_s;
    out.heights = io::settled_centroid_heights(r.file, label, settled_s);
    const std::vector<double>& time = r.file.series("time_s");
    out.profile_y_um = r.file.profile_y_um();
    out.velocity_profile_um_s = analysis::time_average(time, r.file.profile("velocity_x_um_s"), settled_s);
    out.haematocrit_profile = analysis::time_average(time, r.file.profile("haematocrit"), settled_s);
  }
  return out;
}

std::vector<double> block_means(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                                int blocks) {
  const double width = (to - from) / blocks;
  std::vector<double> sum(static_cast<std::size_t>(blocks), 0.0);
  std::vector<int> count(static_cast<std::size_t>(blocks), 0);
  for (std::size_t k = 0; k < y.size() && k < clock.size(); ++k) {
    if (clock[k] < from || clock[k] >= to || !std::isfinite(y[k])) continue;
    const auto b = static_cast<std::size_t>(std::min(blocks - 1, static_cast<int>((clock[k] - from) / width)));
    sum[b] += y[k];
    ++count[b];
  }
  for (std::size_t b = 0; b < sum.size(); ++b) sum[b] = count[b] > 0 ? sum[b] / count[b] : std::nan("");
  return sum;
}

WindowEstimate block_estimate(const std::vector<double>& clock, const std::vector<double>& y, double from, double to,
                              int blocks) {
  const std::vector<double> means = block_means(clock, y, from, to, blocks);
  WindowEstimate e;
  for (double m : means) {
    if (std::isnan(m)) throw std::runtime_error("a block of the settled window is empty");
    e.mean += m / blocks;
  }
  double ss = 0.0;
  for (double m : means) ss += (m - e.mean) * (m - e.mean);
  e.se = std::sqrt(ss / (blocks - 1) / blocks);
  return e;
}

SeedEnsemble combine_seeds(const std::vector<WindowEstimate>& seeds, double t975) {
  if (seeds.size() < 2) throw std::invalid_argument("combine_seeds: fewer than two estimates");
  const double n = static_cast<double>(seeds.size());
  SeedEnsemble out;
  double w_sum = 0.0, wm = 0.0, ss = 0.0;
  for (const WindowEstimate& x : seeds) {
    out.mean += x.mean / n;
    const double w = 1.0 / (x.se * x.se);
    w_sum += w;
    wm += w * x.mean;
  }
  out.weighted_mean = wm / w_sum;
  for (const WindowEstimate& x : seeds) {
    ss += (x.mean - out.mean) * (x.mean - out.mean);
    out.chi2 += (x.mean - out.weighted_mean) * (x.mean - out.weighted_mean) / (x.se * x.se);
  }
  out.ci95 = t975 * std::sqrt(ss / (n - 1.0) / n);
  return out;
}

OneWayAnova one_way_anova(const std::vector<std::vector<double>>& groups) {
  std::size_t total = 0;
  double grand = 0.0;
  for (const auto& g : groups)
    for (double y : g) {
      if (!std::isfinite(y)) throw std::invalid_argument("one_way_anova: a value is not finite");
      grand += y;
      ++total;
    }
  if (groups.size() < 2 || total <= groups.size())
    throw std::invalid_argument("one_way_anova: needs two groups and more values than groups");
  grand /= static_cast<double>(total);
  double between = 0.0, within = 0.0;
  for (const auto& g : groups) {
    if (g.empty()) throw std::invalid_argument("one_way_anova: an empty group");
    double m = 0.0;
    for (double y : g) m += y;
    m /= static_cast<double>(g.size());
    between += static_cast<double>(g.size()) * (m - grand) * (m - grand);
    for (double y : g) within += (y - m) * (y - m);
  }
  OneWayAnova out;
  out.df_between = static_cast<int>(groups.size()) - 1;
  out.df_within = static_cast<int>(total - groups.size());
  out.F = (between / out.df_between) / (within / out.df_within);
  return out;
}

void add_channel_run(io::ResultRecord& record, const ChannelSeries& r, std::map<std::string, io::Value> keys,
                     double from, double to, int blocks, const std::string& label) {
  auto window_mean = [&](const std::vector<double>& y) {
    return r.completed ? block_estimate(r.strain, y, from, to, blocks).mean : std::nan("");
  };
  const double reached = r.strain.empty() ? 0.0 : r.strain.back();
  keys["steps"] = static_cast<double>(r.steps);
  keys["cells"] = static_cast<double>(r.cells);
  keys["strain_reached"] = reached;
  keys["relative_apparent_viscosity"] = window_mean(r.eta);
  keys["cell_free_layer_normalised"] = window_mean(r.cfl);
  keys["discharge_haematocrit"] = window_mean(r.hd);
  keys["max_edge_strain"] = r.max_edge_strain;
  keys["max_area_change"] = r.max_area_change;
  keys["wall_time_s"] = r.wall_s;
  if (r.resumable) {  // the wall time of the last part only when continued or read back
    keys["resumed_from_step"] = static_cast<double>(r.resumed_from_step);
    keys["read_back"] = r.read_back ? 1.0 : 0.0;
  }
  record.add_run(std::move(keys), r.scene_text);
  std::printf("%s: %s at strain %.1f, eta_rel %.4f, delta* %.4f, edge %.3f, area %.4f, %.0f s%s%s\n", label.c_str(),
              r.completed ? "completed" : "stopped", reached, window_mean(r.eta), window_mean(r.cfl), r.max_edge_strain,
              r.max_area_change, r.wall_s, r.completed ? "" : ": ", r.diagnosis.c_str());
}

std::string strain_window(double from, double to) {
  char window[48];
  std::snprintf(window, sizeof window, "strain %g-%g", from, to);
  return window;
}

std::string strain_design(double strain, double from, int blocks) {
  static constexpr const char* kWords[] = {"zero", "one", "two", "three", "four", "five",
                                           "six", "seven", "eight", "nine", "ten"};
  const std::string count = blocks >= 0 && blocks <= 10 ? kWords[blocks] : std::to_string(blocks);
  char text[128];
  std::snprintf(text, sizeof text, "%g strain units, means over %s (%s blocks of %g)", strain,
                strain_window(from, strain).c_str(), count.c_str(), (strain - from) / blocks);
  return text;
}

void add_ensemble_means(io::ResultRecord& record, const std::string& tag, const SeedEnsemble& eta,
                        const SeedEnsemble& cfl, double from, double to) {
  const double lowest = -std::numeric_limits<double>::infinity();
  const std::string window = "over " + strain_window(from, to);
  record.add_metric({"relative_apparent_viscosity_" + tag,
                     "ensemble mean of eta_rel " + window + " (eq 12.1)", "", eta.mean, lowest, 0.0,
                     io::Comparison::at_least, "informative; 95 % half-width " + std::to_string(eta.ci95)});
  record.add_metric({"cell_free_layer_normalised_" + tag,
                     "ensemble mean of delta* " + window + " (eq 12.2)", "", cfl.mean, lowest, 0.0,
                     io::Comparison::at_least, "informative; 95 % half-width " + std::to_string(cfl.ci95)});
}

io::Series dispersion_across_series(const analysis::DispersionProfile& profile, double wall_shear_rate,
                                    const std::string& name, const std::string& title) {
  io::Series s;
  s.name = name;
  s.title = title + " (lag " + fmt("%.3g", profile.lag * wall_shear_rate) + " strain units, eq 12.4b)";
  s.xlabel = "y at the time origin (um)";
  s.ylabel = "D_yy (um^2/s)";
  for (const analysis::DispersionBin& b : profile.bins) {
    if (b.pairs < kAcrossMinPairs) continue;
    s.x.push_back(0.5 * (b.y_from + b.y_to));
    s.y.push_back(b.D);
  }
  return s;
}

}  // namespace erythro::vv
