#include "kernels/fluid_solid_exchange.hpp"

#include <algorithm>

#include "kernels/node_rows.hpp"
#include "kernels/tet_geometry.hpp"
#include "kernels/tet_intersection.hpp"
#include "kernels/tet_point_location.hpp"

namespace rift::kernels {

void tet_mean_vectors(std::span<const double> node_value, std::span<const int32_t> tet_nodes,
                      std::span<double> out, size_t begin, size_t end) {
  for (size_t t = begin; t < end; ++t)
    for (int d = 0; d < 3; ++d) {
      double s = 0.0;
      for (int a = 0; a < 4; ++a) s += node_value[3 * static_cast<size_t>(tet_nodes[4 * t + a]) + d];
      out[3 * t + d] = 0.25 * s;
    }
}

namespace {
void corners(std::span<const double> x, std::span<const int32_t> tet_nodes, int32_t t, double c[4][3]) {
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d)
      c[a][d] = x[3 * static_cast<size_t>(tet_nodes[4 * static_cast<size_t>(t) + a]) + d];
}
}  // namespace

void tet_volume_rates(std::span<const double> x, std::span<const int32_t> tet_nodes, double dt,
                      std::span<double> volume_prev, std::span<double> theta, size_t begin, size_t end) {
  double c[4][3];
  for (size_t t = begin; t < end; ++t) {
    corners(x, tet_nodes, static_cast<int32_t>(t), c);
    const double v = tet_volume(c);
    theta[t] = v != 0.0 && dt > 0.0 ? (v - volume_prev[t]) / (dt * v) : 0.0;
    volume_prev[t] = v;
  }
}

void overlap_volumes(const OverlapArgs& a, size_t begin, size_t end) {
  double k[4][3], s[4][3];
  int32_t last_fluid = -1;
  for (size_t p = begin; p < end; ++p) {
    const CouplingPair& pair = a.pairs[p];
    if (pair.fluid != last_fluid) {  // consecutive pairs share their fluid tet
      corners(a.fluid_x, a.fluid_tet_nodes, pair.fluid, k);
      last_fluid = pair.fluid;
    }
    corners(a.solid_x, a.solid_tet_nodes, pair.solid, s);
    a.volume[p] = tet_intersection_volume(k, s);
  }
}

void pair_ranges(std::span<const CouplingPair> pairs, std::span<int64_t> first) {
  const size_t n_fluid = first.size() - 1;
  size_t p = 0;
  for (size_t k = 0; k <= n_fluid; ++k) {
    while (p < pairs.size() && static_cast<size_t>(pairs[p].fluid) < k) ++p;
    first[k] = static_cast<int64_t>(p);
  }
}

void solid_to_fluid_cells(const SolidToFluidArgs& a, size_t begin, size_t end) {
  for (size_t k = begin; k < end; ++k) {
    double v = 0.0, m[3] = {0.0, 0.0, 0.0}, rate = 0.0;
    for (int64_t p = a.first[k]; p < a.first[k + 1]; ++p) {
      const double w = a.pair_volume[p];
      const size_t s = static_cast<size_t>(a.pairs[p].solid);
      v += w;
      for (int d = 0; d < 3; ++d) m[d] += w * a.solid_velocity[3 * s + d];
      if (!a.solid_dilatation.empty()) rate += w * a.solid_dilatation[s];
    }
    const double alpha = a.fluid_volume[k] > 0.0 ? std::clamp(v / a.fluid_volume[k], 0.0, 1.0) : 0.0;
    a.solid_volume[k] = v;
    a.fraction[k] = alpha;
    for (int d = 0; d < 3; ++d) a.target[3 * k + d] = v > 0.0 ? m[d] / v : 0.0;
    a.sigma[k] = a.beta * a.rho * alpha / a.dt;
    a.pair_weight[k] = v > a.fluid_volume[k] ? a.fluid_volume[k] / v : 1.0;
    if (!a.dilatation.empty())
      a.dilatation[k] = a.fluid_volume[k] > 0.0 ? a.pair_weight[k] * rate / a.fluid_volume[k] : 0.0;
  }
}

void fluid_to_solid_pairs(const FluidToSolidArgs& a, size_t begin, size_t end) {
  const double relax = a.beta * a.rho / a.dt, inertia = a.rho / a.dt;
  for (size_t p = begin; p < end; ++p) {
    const size_t k = static_cast<size_t>(a.pairs[p].fluid);
    const double w = a.pair_weight[k] * a.pair_volume[p];
    for (int d = 0; d < 3; ++d) {
      const double u = a.fluid_velocity[3 * k + d];
      const double penalty = w * relax * (u - a.target[3 * k + d]);
      a.penalty[3 * p + d] = penalty;
      a.force[3 * p + d] = penalty + w * (inertia * (u - a.fluid_velocity_old[3 * k + d]) - a.body_force[d]);
    }
  }
}

void gather_to_solid_nodes(std::span<const CouplingPair> pairs, std::span<const double> pair_value,
                           int components, std::span<const int32_t> solid_tet_nodes,
                           std::span<double> node_value) {
  std::fill(node_value.begin(), node_value.end(), 0.0);
  // Corner k is corner k % 4 of the solid tet of pair k / 4; each takes a quarter of the pair's value.
  const auto node_of = [&](size_t k) {
    return solid_tet_nodes[4 * static_cast<size_t>(pairs[k / 4].solid) + k % 4];
  };
  const size_t m = static_cast<size_t>(components);
  const auto value_of = [&](size_t k) { return &pair_value[m * (k / 4)]; };
  if (components == 3)
    add_corners_to_nodes<3>(4 * pairs.size(), node_of, value_of, 0.25, node_value);
  else
    add_corners_to_nodes<1>(4 * pairs.size(), node_of, value_of, 0.25, node_value);
}

size_t interpolate_p1_at_points(std::span<const double> fluid_x, std::span<const int32_t> fluid_tet_nodes,
                                std::span<const double> field, std::span<const double> points,
                                std::span<const CouplingPair> candidates, std::span<double> out,
                                std::span<int32_t> cell) {
  const size_t n = out.size();
  size_t outside = 0, p = 0;
  for (size_t k = 0; k < n; ++k) {
    double best = -1e300, value = 0.0;
    int32_t winner = -1;
    for (; p < candidates.size() && static_cast<size_t>(candidates[p].fluid) == k; ++p) {
      const size_t t = static_cast<size_t>(candidates[p].solid);
      double c[4][3], lambda[4];
      corners(fluid_x, fluid_tet_nodes, static_cast<int32_t>(t), c);
      tet_barycentric(c, &points[3 * k], lambda);
      const double low = std::min(std::min(lambda[0], lambda[1]), std::min(lambda[2], lambda[3]));
      if (low > best) {
        best = low;
        winner = static_cast<int32_t>(t);
        value = 0.0;
        for (int a = 0; a < 4; ++a)
          value += lambda[a] * field[static_cast<size_t>(fluid_tet_nodes[4 * t + a])];
      }
    }
    const bool found = best >= -1e-9;
    out[k] = found ? value : 0.0;
    if (!cell.empty()) cell[k] = found ? winner : -1;
    outside += found ? 0 : 1;
  }
  return outside;
}

}  // namespace rift::kernels
