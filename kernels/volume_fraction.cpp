#include "kernels/volume_fraction.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

#include "kernels/tet_intersection.hpp"

namespace rift::kernels {

namespace {

constexpr double kMaxCellsPerAxis = 1048576.0;  // 2^20: keys below 2^63

void gather_tet(std::span<const double> x, std::span<const int32_t> tet_nodes, size_t t, double c[4][3]) {
  for (int a = 0; a < 4; ++a) {
    const size_t node = static_cast<size_t>(tet_nodes[4 * t + a]);
    for (int d = 0; d < 3; ++d) c[a][d] = x[3 * node + d];
  }
}

template <class T>
void ensure_size(std::vector<T>& v, size_t n, size_t& grows, bool& grown) {
  if (n <= v.size()) return;
  if (n > v.capacity() && !grown) {
    ++grows;
    grown = true;
  }
  v.resize(n);
}

inline bool overlap(const double* p, const double* q) {
  return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5];
}

// The inflated box k of (lo, hi) as lo' xyz, hi' xyz.
inline void inflated_box(std::span<const double> lo, std::span<const double> hi, size_t k, double h,
                         double out[6]) {
  for (int d = 0; d < 3; ++d) {
    out[d] = lo[3 * k + d] - h;
    out[3 + d] = hi[3 * k + d] + h;
  }
}

// Uniform grid over the solid boxes' lower corners.
struct Grid {
  double origin[3];
  double cell;
  int64_t n[3];
  int64_t index(double x, int d) const { return static_cast<int64_t>(std::floor((x - origin[d]) / cell)); }
  uint64_t key(int64_t ix, int64_t iy, int64_t iz) const {
    return static_cast<uint64_t>((iz * n[1] + iy) * n[0] + ix);
  }
};

Grid make_grid(const CouplingBroadPhaseArgs& args, size_t n_s, double h) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double edge = 0.0;
  for (size_t k = 0; k < n_s; ++k) {
    double box[6];
    inflated_box(args.solid_lo, args.solid_hi, k, h, box);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], box[d]);
      hi[d] = std::max(hi[d], box[d]);
      edge = std::max(edge, box[3 + d] - box[d]);
    }
  }
  Grid g;
  g.cell = edge * (1.0 + 1e-6);
  for (int d = 0; d < 3; ++d) g.cell = std::max(g.cell, (hi[d] - lo[d]) / kMaxCellsPerAxis);
  if (!(g.cell > 0.0)) g.cell = 1.0;  // every box is one and the same point: any cell holds them all
  for (int d = 0; d < 3; ++d) {
    g.origin[d] = lo[d];
    g.n[d] = g.index(hi[d], d) + 1;
  }
  return g;
}

}  // namespace

VolumeFractionStatus volume_fraction(const VolumeFractionArgs& args, size_t begin, size_t end) {
  VolumeFractionStatus status;
  const CouplingPair first{static_cast<int32_t>(begin), INT32_MIN};
  size_t p =
      static_cast<size_t>(std::lower_bound(args.pairs.begin(), args.pairs.end(), first) - args.pairs.begin());
  for (size_t f = begin; f < end; ++f) {
    double sum = 0.0;
    double volume = 0.0;
    if (p < args.pairs.size() && static_cast<size_t>(args.pairs[p].fluid) == f) {
      double fluid[4][3], solid[4][3];
      gather_tet(args.fluid_x, args.fluid_tet_nodes, f, fluid);
      const TetHalfSpaces planes = tet_half_spaces(fluid);
      volume = planes.volume;
      for (; p < args.pairs.size() && static_cast<size_t>(args.pairs[p].fluid) == f; ++p) {
        gather_tet(args.solid_x, args.solid_tet_nodes, static_cast<size_t>(args.pairs[p].solid), solid);
        const double v = clipped_tet_volume(solid, planes);
        sum += v;
        ++status.pairs;
        status.intersecting += v > 0.0;
      }
    }
    const double alpha = volume > 0.0 ? std::clamp(sum / volume, 0.0, 1.0) : 0.0;
    args.solid_volume[f] = sum;
    args.fraction[f] = alpha;
    status.cut += alpha > 0.0 && alpha < 1.0;
  }
  return status;
}

CouplingBroadPhaseStats coupling_broad_phase(const CouplingBroadPhaseArgs& args,
                                             CouplingBroadPhaseWorkspace& ws) {
  CouplingBroadPhaseStats stats;
  ws.pairs.clear();
  const size_t n_f = args.fluid_lo.size() / 3, n_s = args.solid_lo.size() / 3;
  if (n_f == 0 || n_s == 0) return stats;
  const double h = 0.5 * args.buffer;
  const Grid g = make_grid(args, n_s, h);
  stats.cell_size = g.cell;

  bool grown = false;
  ensure_size(ws.cell_of, n_s, ws.grows, grown);
  ensure_size(ws.order, n_s, ws.grows, grown);
  ensure_size(ws.keys, n_s, ws.grows, grown);
  ensure_size(ws.sorted_box, 6 * n_s, ws.grows, grown);
  for (size_t k = 0; k < n_s; ++k) {
    double box[6];
    inflated_box(args.solid_lo, args.solid_hi, k, h, box);
    ws.cell_of[k] = g.key(g.index(box[0], 0), g.index(box[1], 1), g.index(box[2], 2));
    ws.order[k] = static_cast<int32_t>(k);
  }
  std::sort(ws.order.begin(), ws.order.begin() + static_cast<std::ptrdiff_t>(n_s), [&](int32_t a, int32_t b) {
    return ws.cell_of[a] < ws.cell_of[b] || (ws.cell_of[a] == ws.cell_of[b] && a < b);
  });
  for (size_t i = 0; i < n_s; ++i) {
    const size_t k = static_cast<size_t>(ws.order[i]);
    ws.keys[i] = ws.cell_of[k];
    inflated_box(args.solid_lo, args.solid_hi, k, h, &ws.sorted_box[6 * i]);
  }
  const auto keys_begin = ws.keys.begin();
  const auto keys_end = ws.keys.begin() + static_cast<std::ptrdiff_t>(n_s);

  for (size_t f = 0; f < n_f; ++f) {
    double box[6];
    inflated_box(args.fluid_lo, args.fluid_hi, f, h, box);
    // Cells that can hold the lower corner of an overlapping solid box: [lo - c, hi] on each axis.
    int64_t first[3], last[3];
    bool empty = false;
    for (int d = 0; d < 3; ++d) {
      first[d] = std::max<int64_t>(0, g.index(box[d] - g.cell, d));
      last[d] = std::min<int64_t>(g.n[d] - 1, g.index(box[3 + d], d));
      empty |= first[d] > last[d];
    }
    if (empty) continue;
    size_t hits = 0;
    for (int64_t iz = first[2]; iz <= last[2]; ++iz)
      for (int64_t iy = first[1]; iy <= last[1]; ++iy) {
        const uint64_t k_last = g.key(last[0], iy, iz);
        auto it = std::lower_bound(keys_begin, keys_end, g.key(first[0], iy, iz));
        for (size_t i = static_cast<size_t>(it - keys_begin); i < n_s && ws.keys[i] <= k_last; ++i) {
          ++stats.tested;
          if (!overlap(box, &ws.sorted_box[6 * i])) continue;
          ensure_size(ws.hits, hits + 1, ws.grows, grown);
          ws.hits[hits++] = ws.order[i];
        }
      }
    std::sort(ws.hits.begin(), ws.hits.begin() + static_cast<std::ptrdiff_t>(hits));
    for (size_t i = 0; i < hits; ++i) {
      if (ws.pairs.size() == ws.pairs.capacity() && !grown) {
        ++ws.grows;
        grown = true;
      }
      ws.pairs.push_back({static_cast<int32_t>(f), ws.hits[i]});
    }
  }
  stats.pairs = ws.pairs.size();
  return stats;
}

std::vector<CouplingPair> coupling_broad_phase_brute_force(const CouplingBroadPhaseArgs& args) {
  std::vector<CouplingPair> pairs;
  const size_t n_f = args.fluid_lo.size() / 3, n_s = args.solid_lo.size() / 3;
  const double h = 0.5 * args.buffer;
  for (size_t f = 0; f < n_f; ++f) {
    double a[6];
    inflated_box(args.fluid_lo, args.fluid_hi, f, h, a);
    for (size_t s = 0; s < n_s; ++s) {
      double b[6];
      inflated_box(args.solid_lo, args.solid_hi, s, h, b);
      if (overlap(a, b)) pairs.push_back({static_cast<int32_t>(f), static_cast<int32_t>(s)});
    }
  }
  return pairs;
}

}  // namespace rift::kernels
