// validation.doublet_rigid_limit (full): issue 6 item 7. One elliptical cell (a/b = 2,
// stress-free at its initial shape) in shear as its membrane stiffens and its interior
// viscosity rises: the tumbling period approaches Jeffery's T = 2π(a/b + b/a)/γ̇.
// docs/validation-doublet.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/case_support.hpp"
#include "doublet_cases.hpp"
#include "doublet_outcome.hpp"
#include "doublet_record.hpp"

using namespace erythro;

TEST(DoubletShear, RigidLimit) {
  vv::Stopwatch total;
  io::ResultRecord rec("validation.doublet_rigid_limit", "doublet");
  rec.set_requirement(
      "An elliptical cell (a/b = 2) in simple shear tumbles, and as its membrane stiffens (Ca down) and its "
      "interior viscosity rises (ratio up) its tumbling period rises to Jeffery's period and reaches it within the "
      "confinement effect at the stiff end (|T/T_J - 1| <= 0.1).");
  rec.set_reference("Jeffery 1922, Bretherton 1962 (docs/parameters.md, E1): rigid ellipse in 2D simple shear at Re -> 0, "
                    "gamma T = 2 pi (a/b + b/a) = 5 pi for a/b = 2; a quadrant of the orbit takes T/4.");
  const auto levels = vv::rigid_levels();
  std::vector<vv::DoubletRun> plan;
  for (const auto& lv : levels)
    plan.push_back({vv::rigid_config(lv), vv::fmt("Ca=%.4g", lv.capillary) + vv::fmt(" ratio=%.3g", lv.viscosity_ratio)});
  const std::vector<vv::DoubletShearResult> runs = vv::run_doublet_shears(plan, rec.case_name());  // at once
  std::vector<double> gaps;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const vv::DoubletShearConfig& c = plan[i].config;
    const std::string& label = plan[i].label;
    const vv::DoubletShearResult& r = runs[i];
    vv::print_run(label, r);
    if (gaps.empty()) vv::add_mapping(rec, c, r);
    vv::add_row(rec, label, c, r);
    vv::add_histories(rec, label, r);
    vv::add_health_metrics(rec, label, r);
    const double Tq = vv::quadrant_period(r);
    const double TJ = vv::jeffery_period(c.ellipse_axis_ratio);
    const double gap = Tq > 0 ? Tq / TJ - 1.0 : 1e9;
    gaps.push_back(gap);
    rec.set_parameter("period " + label, vv::fmt("gamma T = %.3f", Tq) + vv::fmt(" vs Jeffery %.3f", TJ) +
                                             vv::fmt(" (gap %+.3f)", gap) + vv::fmt("; mean a/b in the quadrant %.3f", r.aspect_quadrant));
    rec.add_metric({"tumbles " + label, "1 if the long axis passed 0 and -90 deg (a quadrant measured)", "",
                    Tq > 0 ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                    "a stress-free ellipse with a viscous interior tumbles; without the quadrant no period"});
  }
  // T along the sequence (gap + 1 = T/T_J).
  int falls = 0;
  for (std::size_t i = 1; i < gaps.size(); ++i)
    if (!(gaps[i] > gaps[i - 1])) ++falls;
  rec.add_metric({"period_rises_with_rigidity", "steps along the sequence where T/T_J does not grow", "",
                  static_cast<double>(falls), 0.0, 0.0, io::Comparison::at_most,
                  "a deformable cell tumbles faster than the rigid ellipse (it shortens while passing the slow, "
                  "flow-aligned orientation); stiffening and a more viscous interior remove that"});
  rec.add_metric({"jeffery_bracketed", "1 if T/T_J - 1 changes sign along the sequence (T_J inside the measured range)",
                  "", gaps.front() < 0 && gaps.back() > 0 ? 1.0 : 0.0, 1.0, 0.0, io::Comparison::at_least,
                  "the deformable end is faster than Jeffery, the stiff end slower (confinement): the rigid limit "
                  "is approached through T_J"});
  rec.add_metric({"gap_stiffest", "|T/T_J - 1| at the stiffest, most viscous level (membrane strain < 1 %)", "",
                  std::abs(gaps.back()), 0.10, 0.0, io::Comparison::at_most,
                  "a rigid ellipse here is slowed by the walls (2a/H = 0.26: a few %) and lattice Re = 0.1; 10 % "
                  "bounds that (measured +6.3 %)"});
  vv::finish_record(rec, total.seconds());
}
