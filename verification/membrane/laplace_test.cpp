// Cases verification.laplace_pressure (full tier: 4 kernels × R = 8, 16, 32) and
// verification.laplace_pressure_ci (CI subset: cosine4 and peskin4 × R = 8, 12, 16).
//
// Requirement: a pre-stressed circular membrane in fluid reaches the Laplace
// pressure jump Δp = T/R between inside and far outside.
// Reference: static equilibrium of a tensioned ring, Δp = T/R (Young–Laplace, 2D).
// Set-up: laplace_run.hpp (scene inflated_circle.toml: λ = 1.05 by cells.prestretch,
// neo-Hookean E_s = 0.02, τ = 1, box 4R, 8R markers, 50R² steps). p = c_s² ρ averaged over r < R − 3 and r > 1.5R; R and T
// from the final markers (mean radius; λ = perimeter / rest perimeter).
// Tolerance: a regular n-gon with tension T carries the inward force 2T sin(π/n)
// per marker, i.e. the jump T/R·sin(π/n)/(π/n) ≈ T/R(1 − π²/6n²) over its circle:
// a second-order membrane-discretisation deficit of 4e-4 at n = 64. The case asserts
// |error| ≤ 2π²/(6n²) (the IB transfer adds no more than the membrane polygon) at
// every stable level and, for the kernel whose error is that polygon term (peskin4),
// observed order 2 ± 0.25 in h/R. Divergence of the narrow kernels is recorded,
// not asserted (docs/verification-ib-membrane.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/case_support.hpp"
#include "common/convergence.hpp"
#include "laplace_run.hpp"

using namespace erythro;

namespace {

void laplace_case(const std::string& case_name, const std::vector<ib::KernelType>& kernels,
                  const std::vector<double>& radii) {
  vv::Stopwatch total;
  io::ResultRecord record(case_name, "membrane");
  record.set_requirement(
      "A pre-stressed circular membrane (lambda = 1.05) in a periodic box reaches the Laplace jump dp = T/R "
      "within twice the membrane-polygon deficit pi^2/(6 n^2) at every resolution where the run is stable; "
      "peskin4 converges at order 2 +- 0.25 in h/R.");
  record.set_reference("2D Young-Laplace law dp = T/R with T = E_s(lambda^3 - 1)/lambda^(3/2) (docs/model.md sec. 3).");
  record.set_parameter("stretch", 1.05);
  record.set_parameter("modulus", 0.02);
  record.set_parameter("tau", 1.0);
  record.set_parameter("box", std::string("periodic 4R x 4R, 8R markers, 50 R^2 steps"));
  record.set_parameter("pressure_regions", std::string("inside r < R - 3, outside r > 1.5 R"));
  for (ib::KernelType k : kernels) {
    const std::string name(ib::to_string(k));
    io::ConvergenceSeries series;
    series.name = name;
    series.norm = "|dp/(T/R) - 1|";
    series.formal_order = 2.0;
    series.order_tolerance = 0.25;
    io::SpeedErrorSeries speed{name, {}, {}, {}};
    bool all_stable = true;
    for (double R : radii) {
      const vv::LaplaceResult r = vv::run_laplace({k, R}, case_name);
      const double n = 8 * R;
      record.add_run({{"kernel", name}, {"R", R}, {"markers", n}, {"diverged", r.diverged ? 1.0 : 0.0},
                      {"steps", double(r.steps)}, {"radius_final", r.radius}, {"stretch_final", r.stretch},
                      {"dp", r.dp}, {"dp_exact", r.dp_exact}, {"error", r.error}, {"polygon_term", r.polygon_term},
                      {"area_loss", r.area_loss}, {"max_fluid_speed", r.max_fluid_speed},
                      {"wall_time_s", r.wall_time_s}},
                     r.scene_text);
      if (r.diverged) {
        all_stable = false;
        continue;
      }
      const double bound = 2 * std::numbers::pi * std::numbers::pi / (6 * n * n);
      EXPECT_TRUE(record.add_metric({"error " + name + " R=" + std::to_string(int(R)),
                                     "|dp/(T/R) - 1| at steady state", "", std::abs(r.error), bound, 0.0,
                                     io::Comparison::at_most,
                                     "twice the n-gon force deficit pi^2/(6n^2): the IB transfer, the kernel "
                                     "smearing (O(h^2/R^2)) and LB compressibility may add at most as much "
                                     "again"}))
          << name << " R=" << R << " error " << r.error;
      series.h.push_back(1.0 / R);
      series.error.push_back(std::abs(r.error));
      speed.wall_time_s.push_back(r.wall_time_s);
      speed.error.push_back(std::abs(r.error));
      speed.label.push_back("R=" + std::to_string(int(R)));
    }
    if (all_stable && radii.size() >= 3) {
      vv::fit_order(series);
      record.add_convergence(series);
      if (k == ib::KernelType::peskin4) {
        EXPECT_TRUE(record.add_metric(vv::order_metric(
            series, "the peskin4 error is the n-gon deficit -pi^2/(6n^2) with n = 8R (measured within 30 %), "
                    "exactly second order; 0.25 allows the small IB part")))
            << series.observed_order;
      }
    }
    record.add_speed_error(speed);
  }
  record.set_wall_time(total.seconds());
  record.write_to_results_dir();
  EXPECT_TRUE(record.passed());
}

}  // namespace

TEST(Laplace, CiSubset) {
  laplace_case("verification.laplace_pressure_ci", {ib::KernelType::cosine4, ib::KernelType::peskin4}, {8, 12, 16});
}

TEST(Laplace, AllKernels) {
  laplace_case("verification.laplace_pressure",
               {ib::KernelType::cosine4, ib::KernelType::peskin4, ib::KernelType::roma3, ib::KernelType::linear2},
               {8, 16, 32});
}
