#pragma once
// Shared by the immersed-drag tests: a solid seen by the fluid as the coupling sees it, through its exact
// volume fraction alpha_K on the fluid's tets (kernels/volume_fraction.hpp: the solid's tets clipped
// against each fluid tet) and an absorption sigma_K = sigma0 alpha_K relaxing the fluid to the solid's
// velocity (zero: held); and the force on the solid, the absorption's reaction summed over cells
// (docs/coupling.md),
//   F = sum_K sigma_K (V_K / 4) sum_a (u_a - u_s),
// which in a steady state is the whole hydrodynamic force on the body (the momentum balance of the fluid
// inside it).
#include <array>
#include <cstdint>
#include <vector>

#include "engine/mesh/tet_mesh.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/volume_fraction.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift::fluid_test {

inline std::vector<double> flat_nodes(const TetMesh& m) {
  std::vector<double> x;
  for (const auto& p : m.nodes) x.insert(x.end(), p.begin(), p.end());
  return x;
}
inline std::vector<int32_t> flat_tets(const TetMesh& m) {
  std::vector<int32_t> t;
  for (const auto& k : m.tets) t.insert(t.end(), k.begin(), k.end());
  return t;
}

// alpha_K of the solid mesh on the fluid mesh.
inline std::vector<double> solid_fraction(const TetMesh& fluid, const TetMesh& solid) {
  const std::vector<double> fx = flat_nodes(fluid), sx = flat_nodes(solid);
  const std::vector<int32_t> ft = flat_tets(fluid), st = flat_tets(solid);
  const size_t nf = fluid.tets.size(), ns = solid.tets.size();
  std::vector<int32_t> fid(nf), sid(ns);
  for (size_t i = 0; i < nf; ++i) fid[i] = static_cast<int32_t>(i);
  for (size_t i = 0; i < ns; ++i) sid[i] = static_cast<int32_t>(i);
  std::vector<double> flo(3 * nf), fhi(3 * nf), slo(3 * ns), shi(3 * ns);
  kernels::tet_bounding_boxes(fx, ft, fid, flo, fhi, 0, nf);
  kernels::tet_bounding_boxes(sx, st, sid, slo, shi, 0, ns);
  kernels::CouplingBroadPhaseWorkspace ws;
  kernels::coupling_broad_phase({flo, fhi, slo, shi, 0.0}, ws);
  std::vector<double> solid_volume(nf), alpha(nf);
  kernels::volume_fraction({fx, ft, sx, st, ws.pairs, solid_volume, alpha}, 0, nf);
  return alpha;
}

// Sets sigma_K = sigma0 alpha_K on the solver (a held solid).
inline void hold_solid(fluid::FluidSolver& solver, const std::vector<double>& alpha, double sigma0) {
  auto sigma = solver.own_sigma();
  for (size_t k = 0; k < alpha.size(); ++k) sigma[k] = sigma0 * alpha[k];
  solver.absorption_changed();
}

// The absorption's reaction on a held solid: the force the fluid exerts on it.
inline std::array<double, 3> absorbed_force(const fluid::FluidSolver& solver) {
  const auto tets = solver.tets();
  const auto vol = solver.volumes();
  const auto u = solver.velocity();
  const auto sigma = solver.absorption();
  std::array<double, 3> f{0, 0, 0};
  for (size_t k = 0; k < vol.size(); ++k) {
    if (sigma[k] == 0.0) continue;
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        f[d] += sigma[k] * 0.25 * vol[k] * u[3 * static_cast<size_t>(tets[4 * k + a]) + d];
  }
  return f;
}

}  // namespace rift::fluid_test
