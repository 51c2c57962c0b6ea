#pragma once
// Step (2) of the index-field update (index_field.cpp): the band of ONE cell, eq 26
// (docs/model.md §5), written into the shared field (FieldWriter, one cell after the
// other) or into lists of the cell's own (CellBand), so that the cells' bands can be found
// in parallel and merged into the field afterwards (IndexField::merge_bands), which gives
// the bits of one cell after the other.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstddef>
#include <limits>
#include <vector>

#include "geometry/domain.hpp"
#include "geometry/polygon.hpp"
#include "interior/edge_table.hpp"
#include "interior/marks.hpp"

namespace erythro::interior::detail {

// The polygon-wide figures of one cell's band pass.
struct BandStats {
  double band_area = 0.0;    // Σ(1 − H(d)) over the cell's band nodes, in box order
  double perimeter = 0.0;    // of the polygon, for the leak bound
  double signed_area = 0.0;  // of the polygon: its orientation, and its area within walls
  bool within_walls = true;  // no wall clips the polygon
  bool wedges = false;       // the band pass used per-edge wedges (else whole capsules)
};

// Writes one cell's band nodes and start candidates into the shared field, with the rules
// of index_field.hpp: overlapping bands keep the minimum I; a node is the start candidate
// of the first cell that finds it. One cell after the other (the serial update), or per
// block of rows with the cells in order (merge_bands): either way every node sees the
// cells in the same order.
struct FieldWriter {
  double* index;
  std::uint8_t* mark;
  int* owner;
  int* candidate;
  std::vector<std::size_t>* changed;           // the nodes this update changed
  std::vector<std::size_t>* starts = nullptr;  // the cell's own start candidates, if wanted
  int cell = 0;
  long band_nodes = 0, overlap_nodes = 0;      // as FillReport

  void band_node(std::size_t k, double h) {  // eq 26 value h
    if (mark[k] == kFree) {
      mark[k] = kBand;
      ++band_nodes;
      changed->push_back(k);
    } else if (owner[k] >= 0 && owner[k] != cell) {
      ++overlap_nodes;
    }
    owner[k] = cell;
    index[k] = std::min(index[k], h);
  }
  // Whether k becomes this cell's start candidate (no earlier cell's).
  bool candidate_node(std::size_t k) {
    if (candidate[k] != 0) return false;
    candidate[k] = cell + 1;
    changed->push_back(k);
    if (starts != nullptr) starts->push_back(k);
    return true;
  }
};

// One cell's band nodes and start candidates as lists, for a merge afterwards (the cells'
// band passes in parallel): the same calls as FieldWriter receives, in the same order.
struct CellBand {
  static constexpr double kCandidate = -1.0;  // h of a start candidate
  std::vector<std::size_t> node;
  std::vector<double> h;                      // eq 26 value, or kCandidate
  std::size_t node_min = 0, node_max = 0;     // the least and greatest of `node` (when not empty)

  void clear() {
    node.clear();
    h.clear();
    node_min = std::numeric_limits<std::size_t>::max();
    node_max = 0;
  }
  void band_node(std::size_t k, double value) {
    node.push_back(k);
    h.push_back(value);
    node_min = std::min(node_min, k);
    node_max = std::max(node_max, k);
  }
  void candidate_node(std::size_t k) { band_node(k, kCandidate); }
};

// Per-thread scratch of the band pass, reused from cell to cell (no allocation once grown).
struct BandScratch {
  EdgeTable edges;                      // the cell's edges and wedges
  std::vector<double> box;              // best signed squared distance per node of the cell's box
                                        // (BoxAxis), +inf where no edge reached (−inf: a candidate found)
  std::vector<std::array<int, 2>> span;  // per box row, the first and last column an edge visited
  struct EdgeRow {
    int row, first, last;  // box row and columns of one edge's row
    double qy;             // node-row height above the edge's first marker
  };
  std::vector<EdgeRow> rows;            // the rows of the current edge
  std::vector<double> box_d, box_h;     // one box row's signed distances and eq-26 values
  std::vector<int> col_node, col_left, col_right;  // per box column: grid column, box neighbours
};

// The band of polygon p (lattice units, counter-clockwise or not, unwrapped past periodic
// sides allowed) on `domain` with band half-width w: its band nodes and start candidates
// to `out` in box order, its figures to `stats`.
void find_band(const geometry::Polygon& p, const geometry::Domain& domain, double w, BandScratch& scratch,
               BandStats& stats, FieldWriter& out);
void find_band(const geometry::Polygon& p, const geometry::Domain& domain, double w, BandScratch& scratch,
               BandStats& stats, CellBand& out);

}  // namespace erythro::interior::detail
