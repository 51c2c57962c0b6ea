#pragma once
// Cell configurations for the index-field verification cases (fill agreement, area
// convergence, benchmark): smooth shapes, randomly deformed and folded shapes with fixed
// seeds, periodic-boundary crossings, small cells, close pairs, cells near walls.
// Lattice units; every polygon counter-clockwise and simple.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"

namespace erythro::vv {

struct CellScene {
  std::string name;
  geometry::Domain domain;
  std::vector<geometry::Polygon> cells;
};

// Deterministic uniform numbers in [0, 1) (64-bit LCG; identical on every platform).
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : s_(seed * 2862933555777941757ULL + 3037000493ULL) {}
  double operator()() {
    s_ = s_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s_ >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t s_;
};

// Star-shaped r(θ) = R[1 + Σ_{k=2}^{modes+1} a_k cos(kθ + φ_k)], Σ|a_k| ≤ amplitude < 1,
// `markers` equally spaced in θ, centred at (cx, cy).
geometry::Polygon random_star(Uniform& u, int markers, double R, double amplitude, int modes, double cx, double cy);
// A folded (strongly non-convex, not star-shaped about its centroid) horseshoe: an annular
// sector of mid radius R, thickness t, opening `gap` radians, rotated by `angle`.
geometry::Polygon horseshoe(int markers, double R, double t, double gap, double angle, double cx, double cy);

// The fill-agreement suite (verification.interior_fill_agreement).
std::vector<CellScene> agreement_suite();

// n biconcave cells (100 markers, equivalent radius a) in a regular arrangement on an
// nx × ny periodic grid (benchmark): columns × rows of slots, cells vertical, no overlap.
CellScene biconcave_array(int n, int nx, int ny, double a);

}  // namespace erythro::vv
