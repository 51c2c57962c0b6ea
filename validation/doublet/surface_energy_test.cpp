// validation.doublet_surface_energy (full): issue 6 item 5. The doublet at 100 1/s over
// surface-energy levels (old reading, De* = k means γ = k·E_S0; docs/model.md eq 4.7): outcome
// (rotates as one / dissociates), contact mode, contact
// area, the tumbling period against Jeffery's period of the doublet's equivalent
// ellipse, and a resolution check of the membrane gap. docs/validation-doublet.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/case_support.hpp"
#include "doublet_cases.hpp"
#include "doublet_outcome.hpp"
#include "doublet_record.hpp"

using namespace erythro;

namespace {
// Membrane gap (µm) at the first sample with γ̇t ≥ t.
double gap_at(const vv::DoubletShearResult& r, double t) {
  for (std::size_t i = 0; i < r.strain_h.size(); ++i)
    if (r.strain_h[i] >= t) return r.gap_h[i];
  return r.gap_h.empty() ? 0.0 : r.gap_h.back();
}
constexpr double kGapTime = 4.0;  // γ̇t of the gap comparison (the extensional quadrant ends near γ̇t ≈ 4.5)
}  // namespace

TEST(DoubletShear, SurfaceEnergy100) {
  vv::Stopwatch total;
  io::ResultRecord rec("validation.doublet_surface_energy", "doublet");
  rec.set_requirement(
      "At 100 1/s (thesis set-up mapped to h = 0.3 um, lattice Re = 0.1) each surface-energy level of the old "
      "reading De* = gamma/E_S0 = 0, 0.25, 0.5, 1 (gamma = De* x 6e-6 J/m2) is classified (rotates as one / "
      "dissociates); the outcome is monotone in De*; the contact area grows with De*; an aggregated pair tumbles "
      "with a period within 30 % of Jeffery's for its equivalent ellipse; the non-adhering pair's membrane gap opens "
      "more on the thesis lattice (h = 0.15 um) than on the study lattice; from a second start with the rims 1.0 um "
      "apart the non-adhering pair dissociates and De* = 0.25 rotates as one.");
  rec.set_reference(
      "Thesis ch. III (docs/model.md section 6; De* = 1..5 at 100 1/s; contact modes flat / sigmoid / relaxed sigmoid); "
      "Zhang, Johnson & Popel 2008 J Biomech 41:47 (a rouleau rotates or separates depending on the relative "
      "strength of the intercellular interaction and the viscous forces) and Bagchi, Johnson & Popel 2005 J Biomech "
      "Eng 127:1070; Jeffery 1922: gamma T = 2 pi (a/b + b/a) (docs/parameters.md, E1).");
  // Every run of the case (levels, the second start, the resolution check), run at once on the
  // case's cores (vv::run_doublet_shears); the record is assembled below in this order.
  const std::vector<double> levels = vv::surface_energy_levels();
  const std::vector<double> wide_levels = vv::wide_start_levels();
  std::vector<vv::DoubletRun> plan;
  for (double de : levels) {
    vv::DoubletShearConfig c = vv::study_config();
    c.old_reading_de_star = de;
    plan.push_back({c, vv::fmt("De*=%.2g", de)});
  }
  for (double de : wide_levels) {
    vv::DoubletShearConfig c = vv::study_config();
    c.old_reading_de_star = de;
    c.initial_gap_m = vv::wide_start_gap_m();
    plan.push_back({c, vv::fmt("De*=%.2g gap 1um", de)});
  }
  vv::DoubletShearConfig fine = vv::study_config();  // the thesis lattice h = 0.15 µm
  fine.h_m = 0.15e-6;
  fine.old_reading_de_star = 0.0;
  vv::DoubletShearConfig fine5 = fine;
  fine5.old_reading_de_star = 0.5;
  fine5.pictures = true;  // the aggregated doublet and its flow at the thesis lattice, for the report
  plan.push_back({fine, "De*=0 h=0.15"});
  plan.push_back({fine5, "De*=0.5 h=0.15"});
  const std::vector<vv::DoubletShearResult> all = vv::run_doublet_shears(plan, rec.case_name());

  std::vector<vv::DoubletShearResult> runs(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(levels.size()));
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const vv::DoubletShearConfig& c = plan[i].config;
    const std::string& label = plan[i].label;
    vv::print_run(label, runs[i]);
    if (i == 0) vv::add_mapping(rec, c, runs[i]);
    vv::add_row(rec, label, c, runs[i]);
    vv::add_histories(rec, label, runs[i]);
    vv::add_health_metrics(rec, label, runs[i]);
  }
  rec.set_parameter("capillary_number", runs.front().capillary0);
  // Classification table (parameters), monotonicity, contact and period.
  int undetermined = 0, inversions = 0, contact_drops = 0;
  double worst = 0;
  int periods = 0;
  std::string dissociating, holding;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const vv::DoubletShearResult& r = runs[i];
    const std::string o = vv::doublet_outcome(r);
    const double Tq = vv::quadrant_period(r);
    const double TJ = r.aspect_quadrant > 0 ? vv::jeffery_period(r.aspect_quadrant) : -1;
    rec.set_parameter(vv::fmt("classification De*=%.2g", levels[i]),
                      o + ", contact " + vv::contact_mode(r) + vv::fmt(", Ca/De* = %.3g", r.capillary0 / levels[i]) +
                          vv::fmt(", mean contact %.3f", vv::mean_contact(r, 1.0)) +
                          vv::fmt(", max S %.2f um", vv::max_sigmoid(r)) + vv::fmt(", gamma T = %.2f", Tq) +
                          vv::fmt(" vs Jeffery %.2f", TJ) + vv::fmt(" (a/b = %.3f)", r.aspect_quadrant));
    if (o == "dissociates") dissociating += vv::fmt(" %.2g", levels[i]);
    else if (o == "rotates as one") holding += vv::fmt(" %.2g", levels[i]);
    else ++undetermined;
    for (std::size_t j = i + 1; j < levels.size(); ++j)  // a higher level must not dissociate when a lower one holds
      if (o == "rotates as one" && vv::doublet_outcome(runs[j]) == "dissociates") ++inversions;
    if (i > 0 && !(vv::mean_contact(r, 1.0) > vv::mean_contact(runs[i - 1], 1.0))) ++contact_drops;
    if (levels[i] > 0 && o == "rotates as one" && Tq > 0 && TJ > 0) {
      worst = std::max(worst, std::abs(Tq / TJ - 1.0));
      ++periods;
    }
  }
  rec.set_parameter("levels dissociating", dissociating.empty() ? std::string("none") : dissociating);
  rec.set_parameter("levels rotating as one", holding.empty() ? std::string("none") : holding);
  rec.set_parameter("transition",
                    dissociating.empty()
                        ? std::string("not in De* = 0..1 from the d* start on this lattice: every level, even De* = 0, "
                                      "stays together (see the resolution check and the 1 um start)")
                        : std::string("between the highest dissociating and the lowest rotating level"));
  rec.add_metric({"all_classified", "runs neither dissociated nor completed half a turn within gamma t = 14", "",
                  static_cast<double>(undetermined), 0.0, 0.0, io::Comparison::at_most,
                  "a pair that rotates as one turns half a revolution in ~T_J/2 ~ 7-9 strain units; 14 leaves room"});
  rec.add_metric({"monotone_in_De", "pairs of levels where the higher one dissociates and the lower one holds", "",
                  static_cast<double>(inversions), 0.0, 0.0, io::Comparison::at_most,
                  "adhesion grows with De* at fixed shear: dissociation can only become less likely"});
  rec.add_metric({"contact_grows_with_De", "steps up in De* where the mean contact area (gt >= 1) does not grow", "",
                  static_cast<double>(contact_drops), 0.0, 0.0, io::Comparison::at_most,
                  "a larger surface energy pulls more membrane within the Morse range (flattening the faces)"});
  rec.add_metric({"period_vs_jeffery",
                  "max over aggregated runs (De* > 0) of |T/T_J - 1|, T = 4 x time of the quadrant theta: 0 -> -90 deg",
                  "", periods > 0 ? worst : 1e9, 0.3, 0.0, io::Comparison::at_most,
                  "the pair is no rigid ellipse: its a/b swings between ~1.1 and ~1.9 during the turn (series "
                  "'axis ratio'), the contact slides (sigmoid), and the box (H = 7.7a) and Re = 0.1 lengthen the "
                  "period; the rigid-limit case gives the gap of a stiff ellipse (~6 %)"});
  // Second start: rims 1.0 µm apart (3.3 h, the film resolved) instead of d* (0.41 µm, 1.4 h).
  // Measured: the non-adhering pair separates past r_c in the first extensional quadrant (it
  // ends as a tandem ~7 µm apart, gap 1.6-3.3 µm) while De* = 0.25 pulls the rims to
  // 0.83 µm and turns as one: from this start the transition lies in 0 < De* <= 0.25.
  int wide_expected = 0;
  std::string wide_summary;
  for (std::size_t i = 0; i < wide_levels.size(); ++i) {
    const vv::DoubletShearConfig& c = plan[levels.size() + i].config;
    const std::string& label = plan[levels.size() + i].label;
    const vv::DoubletShearResult& r = all[levels.size() + i];
    vv::print_run(label, r);
    vv::add_row(rec, label, c, r);
    vv::add_health_metrics(rec, vv::fmt("De*=%.2g_gap1um", wide_levels[i]), r);
    if (i == 0) vv::add_histories(rec, label, r);
    const std::string o = vv::doublet_outcome(r);
    const double max_gap = r.gap_h.empty() ? 0.0 : *std::max_element(r.gap_h.begin(), r.gap_h.end());
    rec.set_parameter("classification " + label,
                      o + vv::fmt(", dissociation at gamma t = %.2f", r.dissociation_strain) +
                          vv::fmt(", max gap %.3f um", max_gap));
    // The lowest level (the non-adhering control) is expected to separate, the highest to hold.
    if (i == 0 && o == "dissociates") ++wide_expected;
    if (i + 1 == wide_levels.size() && o == "rotates as one") ++wide_expected;
    wide_summary += vv::fmt(" De* = %.2g: ", wide_levels[i]) + o + ";";
  }
  rec.set_parameter("transition from the 1 um start", "lies between the levels:" + wide_summary);
  rec.add_metric({"transition_bracketed_wide_start",
                  "rims 1.0 um apart at start: De* = 0 dissociates (+1) and De* = 0.25 rotates as one (+1)", "",
                  static_cast<double>(wide_expected), 2.0, 0.0, io::Comparison::at_least,
                  "from d* (1.4h, film not resolved) no level separates even over a full revolution; from 1.0 um "
                  "(3.3h) the extensional quadrant carries the non-adhering pair beyond r_c (first at gamma t = 2.1 by "
                  "0.07 um, again from gamma t = 4 to 9 up to 3.35 um in the exploration) while De* = 0.25 closes the rims to ~0.83 um within the Morse range (1.79 um): the "
                  "start brackets the transition, 0 < De*_c <= 0.25 (De* = 0.1 separates marginally, not asserted)"});
  // Resolution check on the thesis lattice h = 0.15 µm (a/h = 26, 200 × 200, ≈ 41 000 steps per
  // strain unit): the non-adhering pair (membrane gap, outcome) and De* = 0.5 (outcome, period).
  const vv::DoubletShearResult& rf = all[all.size() - 2];
  vv::print_run("De*=0 h=0.15", rf);
  vv::add_row(rec, "De*=0 h=0.15", fine, rf);
  vv::add_health_metrics(rec, "De*=0_h0.15", rf);
  const vv::DoubletShearResult& rf5 = all.back();
  vv::print_run("De*=0.5 h=0.15", rf5);
  vv::add_row(rec, "De*=0.5 h=0.15", fine5, rf5);
  vv::add_histories(rec, "De*=0.5 h=0.15", rf5);
  vv::add_health_metrics(rec, "De*=0.5_h0.15", rf5);
  for (auto [label, rr] : {std::pair{"De*=0 h=0.15", &rf}, std::pair{"De*=0.5 h=0.15", &rf5}}) {
    const double Tq = vv::quadrant_period(*rr);
    const double TJ = rr->aspect_quadrant > 0 ? vv::jeffery_period(rr->aspect_quadrant) : -1;
    rec.set_parameter(std::string("classification ") + label,
                      vv::doublet_outcome(*rr) + ", contact " + vv::contact_mode(*rr) +
                          vv::fmt(", mean contact %.3f", vv::mean_contact(*rr, 1.0)) +
                          vv::fmt(", max gap %.3f um", *std::max_element(rr->gap_h.begin(), rr->gap_h.end())) +
                          vv::fmt(", gamma T = %.2f", Tq) + vv::fmt(" vs Jeffery %.2f", TJ) +
                          vv::fmt(" (a/b = %.3f)", rr->aspect_quadrant) + " (not asserted)");
  }
  {
    io::Series s;
    s.name = "De*=0 h=0.15 separation";
    s.title = s.name;
    s.xlabel = "gamma t";
    s.ylabel = "separation of centres (um), thesis lattice";
    s.x = rf.strain_h;
    s.y = rf.separation_h;
    rec.add_series(s);
    s.name = "De*=0 membrane gap, h=0.15 (y) and h=0.3 (reference)";
    s.title = s.name;
    s.ylabel = "smallest membrane gap (um)";
    s.y = rf.gap_h;
    s.y_reference = runs.front().gap_h;
    s.y_reference.resize(std::min(s.y_reference.size(), s.x.size()));
    s.x.resize(std::min(s.x.size(), runs.front().gap_h.size()));
    s.y.resize(s.x.size());
    rec.add_series(s);
  }
  const double g_fine = gap_at(rf, kGapTime), g_coarse = gap_at(runs.front(), kGapTime);
  rec.set_parameter("resolution check", vv::fmt("De* = 0 gap at gamma t = 4: %.3f um (h = 0.15)", g_fine) +
                                            vv::fmt(" vs %.3f um (h = 0.3)", g_coarse) +
                                            vv::fmt("; Morse cut-off %.2f um", fine.r0_m * 1e6 + fine.cutoff_k / fine.beta_per_m * 1e6));
  rec.add_metric({"gap_opens_when_resolved", "De* = 0: membrane gap at gamma t = 4, h = 0.15 um over h = 0.3 um", "",
                  g_coarse > 0 ? g_fine / g_coarse : 0.0, 1.5, 0.0, io::Comparison::at_least,
                  "the IB kernel spans 4h: two membranes closer than ~2h interpolate nearly the same velocity, so the "
                  "fluid film between them is not resolved and the pair cannot separate; the start gap d* = 0.41 um is "
                  "1.4h at h = 0.3 but 2.7h at h = 0.15, where the extensional quadrant opens it (measured x2.2 in "
                  "the exploration); 1.5 separates the two behaviours"});
  vv::finish_record(rec, total.seconds());
}
