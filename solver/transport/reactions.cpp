#include "transport/reactions.hpp"

#include <algorithm>

namespace erythro::transport {

double no_production(double P_torr, double R_max, double Km_eNOS) {
  const double P = std::max(P_torr, 0.0);
  return R_max * P / (P + Km_eNOS);  // R1
}

double no_r_max_from_shear(double wall_shear_pa) { return 50.0 * wall_shear_pa / 2.4; }

double first_order_consumption(double C, double k) { return k * C; }  // R2

double no_scavenging_rate(double k2_per_molar_second, double heme_uM) {
  return k2_per_molar_second * heme_uM * 1e-6;  // R3: µM → M
}

double no_core_scavenging_rate(double lambda_blood, double R, double delta) {
  const double r = R / (R - delta);
  return 0.5 * lambda_blood * (1.0 + r * r);  // R4
}

double o2_consumption(double P_torr, double C_NO, double Q_max, double Km_torr, double C_ref) {
  const double P = std::max(P_torr, 0.0);
  return Q_max * P / (P + Km_torr * (1.0 + C_NO / C_ref));  // R5
}

}  // namespace erythro::transport
