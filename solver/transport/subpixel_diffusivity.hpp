#pragma once
// Diffusivity of the nodes cut by a curved diffusivity jump (a membrane with D_in inside,
// D_out outside), docs/transport.md §1 "Curved diffusivity jumps", eqs T9–T10.
//
//  series (T9, the former rule):  1/D_n = φ_n/D_in + (1 − φ_n)/D_out  (isotropic, harmonic mean
//                                 over the node's square; φ_n = area fraction inside)
//  subpixel tensor (T10; Farjadpour et al. 2006, Opt Lett 31:2972; Kottke, Farjadpour &
//  Johnson 2008, Phys Rev E 77:036611): with n the interface normal in the node's square and
//  P = n nᵀ its projector,
//      D_n = ⟨1/D⟩⁻¹ P + ⟨D⟩ (I − P),  ⟨1/D⟩⁻¹ = series mean,  ⟨D⟩ = φ D_in + (1 − φ) D_out:
//  the flux across the interface sees the resistances in series, the flux along it the
//  conductances in parallel — the exact effective tensor of a planar laminate, which removes
//  the first-order error of a smoothed interface. On each node's square it needs the tensor
//  lattice (T8; measured: not second order); on each FACE's dual cell (subpixel_face_targets) it
//  is imposed by FaceFluxCorrection (T11): second order (verification.transport_curved_interface).
#include <cstddef>
#include <vector>

#include "geometry/polygon.hpp"
#include "transport/face_flux_correction.hpp"

namespace erythro::transport {

// Treatment of the nodes a membrane cuts: the isotropic series mean (T9, the former rule),
// the node subpixel tensor (T10 on each node's square, tensor lattice T8), or the face
// subpixel tensor (T10 on each face's dual cell, imposed on the series lattice by the
// face-flux correction T11).
enum class InterfaceRule { series, node_tensor, face_tensor };

struct DiffusivityTensor {
  double xx = 0.0, yy = 0.0, xy = 0.0;
};

// One node cut by (or inside) a polygon: area fraction φ ∈ (0, 1] of the node's unit square
// inside, and the unit OUTWARD interface normal averaged over the polygon's edges within the
// square, weighted by their clipped lengths ((0, 0) when no edge crosses the square).
struct CutCell {
  std::size_t node = 0;
  double phi = 0.0;
  double nx = 0.0, ny = 0.0;
};

// Node `node` with the fraction φ ∈ (0, 1] of its square inside a polygon.
struct AreaFraction {
  std::size_t node = 0;
  double phi = 0.0;
};

// Every node of an nx × ny grid (node (i, j) owning the square [i, i+1] × [j, j+1], lattice
// units) with φ > 0 for polygon p, row by row: φ by exact polygon–square clipping
// (geometry::area_in_box).
std::vector<AreaFraction> area_fractions(const geometry::Polygon& p, int nx, int ny);

// The same nodes with, where 0 < φ < 1, the membrane's normal in the square (Liang–Barsky
// clipping of each edge to the square).
std::vector<CutCell> cut_cells(const geometry::Polygon& p, int nx, int ny);

double series_diffusivity(double phi, double D_in, double D_out);    // eq T9
double parallel_diffusivity(double phi, double D_in, double D_out);  // ⟨D⟩
// eq T10; with a zero normal (no edge in the square) the isotropic series value.
DiffusivityTensor subpixel_diffusivity(const CutCell& c, double D_in, double D_out);

// The node_tensor rule: eq T10 on each node of `cells` into lat's diffusivity tensor (D2Q5 TRT;
// D_in, D_out in lattice units).
void set_node_subpixel_tensor(TransportLattice& lat, const std::vector<CutCell>& cells, double D_in, double D_out);

// Face-centred subpixel targets (eq T10 on each face's dual cell, for FaceFluxCorrection eq T11):
// for every x-face (between node (i, j) and (i+1, j)) and y-face near polygon p, the dual cell is
// the unit square centred on the face ([i+½, i+3/2] × [j, j+1], resp. [i, i+1] × [j+½, j+3/2]);
// its φ and normal give the tensor D_f, and the target flux across the face is
//   x-face: K = D_f,xx, X = D_f,xy;   y-face: K = D_f,yy, X = D_f,xy
// (F = −D_f ∇C discretised with the normal difference and the transverse mean difference).
// Dual cells fully inside: K = D_in; fully outside: D_out. Faces within one node of p's
// bounding box are listed (the correction drops those equal to the lattice's own flux).
std::vector<FaceTarget> subpixel_face_targets(const geometry::Polygon& p, int nx, int ny, double D_in, double D_out);

}  // namespace erythro::transport
