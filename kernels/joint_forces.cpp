#include "kernels/joint_forces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/joint_break.hpp"
#include "kernels/vec3_ops.hpp"

namespace rift::kernels {

namespace {

// The mid-surface frame of one joint and its node-pair jumps.
struct JointGeometry {
  double d[3][3];  // d_i = x_i - x_{i+3} (+ the joint's initial offset, when one is given)
  double n[3];     // unit normal, from side B into side A
  double area;     // A
  double h;        // shortest mid-surface edge
  bool ok;         // area > 0 and finite
};

// offset: the joint's initial offset (3 doubles) or nullptr.
[[gnu::always_inline]] inline JointGeometry geometry(std::span<const double> x, const int32_t* nodes,
                                                     const double* offset) {
  JointGeometry g;
  double xm[3][3];
  for (int i = 0; i < 3; ++i) {
    const double* a = &x[3 * static_cast<size_t>(nodes[i])];
    const double* b = &x[3 * static_cast<size_t>(nodes[i + 3])];
    for (int k = 0; k < 3; ++k) {
      xm[i][k] = 0.5 * (a[k] + b[k]);
      g.d[i][k] = a[k] - b[k];
    }
  }
  if (offset)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) g.d[i][k] = g.d[i][k] + offset[k];
  double e1[3], e2[3], e3[3], c[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = xm[1][k] - xm[0][k];
    e2[k] = xm[2][k] - xm[0][k];
    e3[k] = xm[2][k] - xm[1][k];
  }
  cross(e1, e2, c);
  const double twice_area = std::sqrt(dot(c, c));
  g.ok = twice_area > 0.0 && std::isfinite(twice_area);
  const double inv = g.ok ? 1.0 / twice_area : 0.0;
  for (int k = 0; k < 3; ++k) g.n[k] = c[k] * inv;
  g.area = 0.5 * twice_area;
  g.h = std::sqrt(std::min({dot(e1, e1), dot(e2, e2), dot(e3, e3)}));
  return g;
}

// Opening and slip at point (N0, N1, N2); sv receives the sliding vector.
inline void point_jump(const JointGeometry& g, const std::array<double, 3>& N, double& o, double sv[3],
                       double& s) {
  double d[3];
  for (int k = 0; k < 3; ++k) d[k] = N[0] * g.d[0][k] + N[1] * g.d[1][k] + N[2] * g.d[2][k];
  o = dot(d, g.n);
  for (int k = 0; k < 3; ++k) sv[k] = d[k] - o * g.n[k];
  s = std::sqrt(dot(sv, sv));
}

void write_zero_force(const JointArgs& a, size_t j) {
  std::fill_n(&a.corner_force[9 * j], 9, 0.0);
  if (!a.stored_energy.empty()) a.stored_energy[j] = 0.0;
}

// A broken joint: no force, but the aperture and slip stay visible (the fluid model needs the aperture).
// They are the geometric jump: the initial offset belongs to the law, which no longer applies.
void broken_joint(const JointArgs& a, size_t j) {
  write_zero_force(a, j);
  if (!a.damage.empty()) a.damage[j] = 1.0;
  if (a.opening.empty() && a.slip.empty()) return;
  const JointGeometry g = geometry(a.x, &a.joint_nodes[6 * j], nullptr);
  double mean_o = 0.0, mean_s = 0.0;
  if (g.ok) {
    const JointRule& rule = *a.rule;
    for (int q = 0; q < rule.points; ++q) {
      double o, sv[3], s;
      point_jump(g, rule.N[q], o, sv, s);
      mean_o += rule.w[q] * o;
      mean_s += rule.w[q] * s;
    }
  }
  if (!a.opening.empty()) a.opening[j] = mean_o;
  if (!a.slip.empty()) a.slip[j] = mean_s;
}

void write_optional(std::span<double> out, size_t j, double value) {
  if (!out.empty()) out[j] = value;
}

}  // namespace

JointStatus joint_forces_scalar(const JointArgs& a, size_t begin, size_t end) {
  JointStatus status;
  const JointRule& rule = *a.rule;
  const size_t P = static_cast<size_t>(rule.points);
  const double Z = softening_integral();
  for (size_t j = begin; j < end; ++j) {
    if (a.broken[j] != 0) {
      broken_joint(a, j);
      continue;
    }
    const JointGeometry g =
        geometry(a.x, &a.joint_nodes[6 * j], a.initial_offset.empty() ? nullptr : &a.initial_offset[3 * j]);
    if (!g.ok) {
      ++status.degenerate;
      write_zero_force(a, j);
      write_optional(a.opening, j, 0.0);
      write_optional(a.slip, j, 0.0);
      write_optional(a.damage, j, 0.0);
      continue;
    }
    const JointMaterial& m = a.materials[static_cast<size_t>(a.material[j])];
    const JointScales k = joint_scales(m, g.h, a.softening, Z);
    bool short_softening = k.short_normal;
    double F[3][3] = {};  // sum_q w A N_i t, per side-A corner
    double mean_o = 0.0, mean_s = 0.0, energy = 0.0, damage = 0.0, normal_sum = 0.0, shear_sum = 0.0;
    int failed = 0;
    double* history = &a.d_max[P * j];
    double* anchor =
        m.residual_friction > 0.0 && !a.residual_anchor.empty() ? &a.residual_anchor[3 * P * j] : nullptr;
    for (size_t q = 0; q < P; ++q) {
      double o, sv[3], s;
      point_jump(g, rule.N[q], o, sv, s);
      JointPointResponse r = joint_point_response(m, k, a.softening, Z, o, s, history[q]);
      joint_law::settle_tractions(r);
      status.damage_onsets += history[q] == 0.0 && r.d_max > 0.0;
      history[q] = r.d_max;
      failed += r.d_max >= 1.0;
      short_softening |= r.short_shear;
      normal_sum += r.normal_part;
      shear_sum += r.shear_part;
      damage = std::max(damage, r.d_max);
      const double wA = rule.w[q] * g.area;
      mean_o += rule.w[q] * o;
      mean_s += rule.w[q] * s;
      energy += wA * r.energy;
      double t[3];
      for (int c = 0; c < 3; ++c) t[c] = r.sigma * g.n[c] + r.tau_per_slip * sv[c];
      if (anchor && r.d_max > 0.0) {  // damaged: the residual slider (its anchor rests while intact)
        double tr[3];
        energy += wA * residual_friction(r.residual_cap, 0.5 * k.stiffness, sv, g.n, &anchor[3 * q], tr);
        for (int c = 0; c < 3; ++c) t[c] += tr[c];
      }
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) F[i][c] += wA * rule.N[q][i] * t[c];
    }
    status.short_softening += short_softening;
    write_optional(a.opening, j, mean_o);
    write_optional(a.slip, j, mean_s);
    if (failed >= rule.fail_count) {
      joint_detail::record_break(
          a, j, normal_sum >= shear_sum ? JointBreakMode::tensile : JointBreakMode::shear, energy, status);
      write_zero_force(a, j);
      write_optional(a.damage, j, 1.0);
      continue;
    }
    double* f = &a.corner_force[9 * j];  // side B; side A is minus this
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) f[3 * i + c] = F[i][c];
    write_optional(a.damage, j, damage);
    write_optional(a.stored_energy, j, energy);
  }
  return status;
}

#ifndef __AVX2__
JointStatus joint_forces(const JointArgs& args, size_t begin, size_t end) {
  return joint_forces_scalar(args, begin, end);
}
bool joint_forces_vectorised() {
  return false;
}
#endif

double joint_stable_step(std::span<const double> x, std::span<const int32_t> joint_nodes,
                         std::span<const int32_t> material, std::span<const JointMaterial> materials,
                         std::span<const double> node_mass, std::span<const uint8_t> broken, size_t begin,
                         size_t end) {
  double dt = std::numeric_limits<double>::infinity();
  for (size_t j = begin; j < end; ++j) {
    if (!broken.empty() && broken[j] != 0) continue;
    const int32_t* nodes = &joint_nodes[6 * j];
    const JointGeometry g = geometry(x, nodes, nullptr);
    if (!g.ok) continue;
    double m_min = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 6; ++i) m_min = std::min(m_min, node_mass[static_cast<size_t>(nodes[i])]);
    const double p = materials[static_cast<size_t>(material[j])].penalty;
    dt = std::min(dt, std::sqrt(6.0 * g.h * m_min / (p * g.area)));
  }
  return dt;
}

void add_joint_node_stiffness(std::span<const double> x, std::span<const int32_t> joint_nodes,
                              std::span<const int32_t> material, std::span<const JointMaterial> materials,
                              std::span<const uint8_t> broken, std::span<double> stiffness) {
  for (size_t j = 0; j < joint_nodes.size() / 6; ++j) {
    if (!broken.empty() && broken[j] != 0) continue;
    const int32_t* nodes = &joint_nodes[6 * j];
    const JointGeometry g = geometry(x, nodes, nullptr);
    if (!g.ok) continue;
    const double k = 2.0 * materials[static_cast<size_t>(material[j])].penalty * g.area / (3.0 * g.h);
    for (int i = 0; i < 6; ++i) stiffness[static_cast<size_t>(nodes[i])] += k;
  }
}

}  // namespace rift::kernels
