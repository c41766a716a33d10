// The scalar reference: one tet at a time through the shared law body (tet_law.hpp).
#include "kernels/tet_forces.hpp"
#include "kernels/tet_law.hpp"

namespace rift::kernels {

namespace {

void write_zeros(const TetForceArgs& args, size_t t) {
  for (int n = 0; n < 12; ++n) args.corner_force[12 * (t - args.corner_force_first) + n] = 0.0;
  if (!args.stress.empty())
    for (int n = 0; n < 6; ++n) args.stress[6 * t + n] = 0.0;
  if (!args.strain_energy.empty()) args.strain_energy[t] = 0.0;
  if (!args.viscous_power.empty()) args.viscous_power[t] = 0.0;
}

[[gnu::always_inline]] inline void write_response(const TetForceArgs& args, size_t t,
                                                  const tet_law::Response<double>& r) {
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      args.corner_force[12 * (t - args.corner_force_first) + 3 * a + i] = r.force[a][i];
  if (!args.stress.empty())
    for (int n = 0; n < 6; ++n) args.stress[6 * t + n] = r.stress[n];
  if (!args.strain_energy.empty()) args.strain_energy[t] = r.energy;
  if (!args.viscous_power.empty()) args.viscous_power[t] = r.power;
}

// kPrestress: an initial stress is given; without, it is compile-time absent.
template <bool kPrestress>
TetForceStatus forces(const TetForceArgs& args, size_t begin, size_t end) {
  TetForceStatus status;
  tet_law::Wanted<double> want;
  want.energy = !args.strain_energy.empty();
  want.power = !args.viscous_power.empty();
  for (size_t t = begin; t < end; ++t) {
    double x[4][3], v[4][3], dm[9];
    for (int a = 0; a < 4; ++a) {
      const size_t node = static_cast<size_t>(args.tet_nodes[4 * t + a]);
      for (int i = 0; i < 3; ++i) {
        x[a][i] = args.x[3 * node + i];
        v[a][i] = args.v[3 * node + i];
      }
    }
    for (int n = 0; n < 9; ++n) dm[n] = args.dm_inv[9 * t + n];
    const double volume0 = args.volume0[t];
    tet_law::Kinematics<double> k;
    double ex[3][3], ev[3][3];
    tet_law::edges(x, ex);
    tet_law::edges(v, ev);
    tet_law::kinematics(ex, dm, k);
    if (!(volume0 > 0.0) || !(k.J > 0.0)) {
      if (volume0 > 0.0 && status.inverted++ == 0) status.first_inverted = static_cast<int64_t>(t);
      write_zeros(args, t);
      continue;
    }
    const size_t mat = static_cast<size_t>(args.material[t]);
    const TetMaterial& m = args.materials[mat];
    const tet_law::Constants<double> c{m.lambda, m.mu, m.eta, volume0};
    if (kPrestress) want.sigma0 = &args.initial_stress[6 * mat];
    tet_law::Response<double> r;
    tet_law::response(k, ev, dm, c, want.energy ? tet_law::excess_log(k.j) : 0.0, want, r);
    write_response(args, t, r);
  }
  return status;
}

}  // namespace

TetForceStatus tet_forces_scalar(const TetForceArgs& args, size_t begin, size_t end) {
  return args.initial_stress.empty() ? forces<false>(args, begin, end) : forces<true>(args, begin, end);
}

#ifndef __AVX2__
TetForceStatus tet_forces(const TetForceArgs& args, size_t begin, size_t end) {
  return tet_forces_scalar(args, begin, end);
}
bool tet_forces_vectorised() {
  return false;
}
#endif

}  // namespace rift::kernels
