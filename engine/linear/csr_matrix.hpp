#pragma once
// Compressed sparse row matrix with a fixed pattern: built once from the node graph of a tet mesh (entry
// (i, j) exists when nodes i and j share a tet, columns sorted per row), values refilled in place each
// step through per-tet slot maps (kernels/fluid_element.hpp), so the time-step loop allocates nothing.
#include <cstdint>
#include <span>
#include <vector>

namespace rift {

struct CsrMatrix {
  int32_t rows = 0;
  std::vector<int32_t> row_ptr;  // rows + 1
  std::vector<int32_t> col;      // nnz, sorted within each row
  std::vector<double> val;       // nnz

  size_t nnz() const { return col.size(); }
  // Position of (i, j) in val, -1 when not in the pattern (binary search; set-up only).
  int32_t find(int32_t i, int32_t j) const;
  // y = A x.
  void multiply(std::span<const double> x, std::span<double> y) const;
  // Rows [begin, end) of y = A x (rows are independent: blocks of rows may run in parallel).
  void multiply_rows(std::span<const double> x, std::span<double> y, size_t begin, size_t end) const;
};

// Pattern of the P1 node graph of tets (4 node indices per tet), values zero.
CsrMatrix p1_pattern(int32_t n_nodes, std::span<const int32_t> tet_nodes);
// slot[16 t + 4 a + b] = position of (node_a, node_b) of tet t in val.
std::vector<int32_t> p1_tet_slots(const CsrMatrix& m, std::span<const int32_t> tet_nodes);
// Position of each diagonal entry.
std::vector<int32_t> diagonal_slots(const CsrMatrix& m);

}  // namespace rift
