#pragma once
// Reaction rates of the NO/O2 model, one small function each (docs/transport.md §4;
// docs/parameters.md "NO / O2 transport"). Units: µM, Torr, s unless stated; rates are
// amounts per unit volume per unit time (µM/s). Consumption rates are returned
// positive (a sink of −rate in eq T1).
namespace erythro::transport {

// eNOS production in the endothelium (R1): R_NO = R_max P / (P + K_m,eNOS). The EC
// uses O2 1:1 with NO produced: the O2 sink equals this rate.
double no_production(double P_torr, double R_max, double Km_eNOS = 4.7);

// R_max of eq R1 from the wall shear stress (docs/parameters.md): 50 µM/s × τ_w / 2.4 Pa.
double no_r_max_from_shear(double wall_shear_pa);

// First-order consumption (R2): rate = k C (NO in SM / tissue, k = 1 s⁻¹; NO scavenging
// by Hb in an RBC interior with k = no_scavenging_rate()).
double first_order_consumption(double C, double k);

// Effective first-order NO scavenging constant inside an RBC (R3):
// k = k_NO,Hb × [heme]; k2 in 1/(M s), heme in µM → k in 1/s
// (1.4e5 M⁻¹s⁻¹ × 20.3 mM = 2842 s⁻¹).
double no_scavenging_rate(double k2_per_molar_second = 1.4e5, double heme_uM = 20.3e3);

// Whole-blood core scavenging with a cell-free layer δ (docs/parameters.md, core rate; R4):
// λ_core = (λ_b/2)[1 + R²/(R − δ)²].
double no_core_scavenging_rate(double lambda_blood, double R, double delta);

// Michaelis–Menten O2 consumption inhibited by NO (R5):
// Q = Q_max P / [P + K_m (1 + C_NO / C_ref)],  C_NO and C_ref in the same unit.
double o2_consumption(double P_torr, double C_NO, double Q_max, double Km_torr = 1.0, double C_ref = 27e-3);

}  // namespace erythro::transport
