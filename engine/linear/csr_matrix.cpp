#include "engine/linear/csr_matrix.hpp"

#include <algorithm>
#include <stdexcept>

namespace rift {

int32_t CsrMatrix::find(int32_t i, int32_t j) const {
  const auto first = col.begin() + row_ptr[i], last = col.begin() + row_ptr[i + 1];
  const auto it = std::lower_bound(first, last, j);
  return it != last && *it == j ? static_cast<int32_t>(it - col.begin()) : -1;
}

void CsrMatrix::multiply(std::span<const double> x, std::span<double> y) const {
  multiply_rows(x, y, 0, static_cast<size_t>(rows));
}

void CsrMatrix::multiply_rows(std::span<const double> x, std::span<double> y, size_t begin,
                              size_t end) const {
  for (size_t i = begin; i < end; ++i) {
    double s = 0.0;
    for (int32_t k = row_ptr[i]; k < row_ptr[i + 1]; ++k) s += val[k] * x[col[k]];
    y[i] = s;
  }
}

CsrMatrix p1_pattern(int32_t n_nodes, std::span<const int32_t> tet_nodes) {
  std::vector<std::vector<int32_t>> adj(static_cast<size_t>(n_nodes));
  for (int32_t n = 0; n < n_nodes; ++n) adj[n].push_back(n);
  const size_t n_tets = tet_nodes.size() / 4;
  for (size_t t = 0; t < n_tets; ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) adj[tet_nodes[4 * t + a]].push_back(tet_nodes[4 * t + b]);
  CsrMatrix m;
  m.rows = n_nodes;
  m.row_ptr.assign(static_cast<size_t>(n_nodes) + 1, 0);
  for (int32_t n = 0; n < n_nodes; ++n) {
    auto& r = adj[n];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    m.row_ptr[n + 1] = m.row_ptr[n] + static_cast<int32_t>(r.size());
  }
  m.col.reserve(m.row_ptr.back());
  for (const auto& r : adj) m.col.insert(m.col.end(), r.begin(), r.end());
  m.val.assign(m.col.size(), 0.0);
  return m;
}

std::vector<int32_t> p1_tet_slots(const CsrMatrix& m, std::span<const int32_t> tet_nodes) {
  const size_t n_tets = tet_nodes.size() / 4;
  std::vector<int32_t> slot(16 * n_tets);
  for (size_t t = 0; t < n_tets; ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int32_t s = m.find(tet_nodes[4 * t + a], tet_nodes[4 * t + b]);
        if (s < 0) throw std::logic_error("p1_tet_slots: entry not in the pattern");
        slot[16 * t + 4 * a + b] = s;
      }
  return slot;
}

std::vector<int32_t> diagonal_slots(const CsrMatrix& m) {
  std::vector<int32_t> d(static_cast<size_t>(m.rows));
  for (int32_t i = 0; i < m.rows; ++i) {
    d[i] = m.find(i, i);
    if (d[i] < 0) throw std::logic_error("diagonal_slots: missing diagonal");
  }
  return d;
}

}  // namespace rift
