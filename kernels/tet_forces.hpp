#pragma once
// Internal force, Cauchy stress and strain energy of 4-node constant-strain tetrahedra, Y3D law
// (docs/reference femdem.md 1a, Lei's Yfd3TET4ELS):
//   F = FX F0^-1,  L = LX FX^-1,  B = F F^T,  D = sym L,  J = det F
//   sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I + eta D
//   W     = mu/2 (tr C - 3) - mu ln J + lambda/4 (J^2 - 1 - 2 ln J)      per unit reference volume
// The elastic part is the Cauchy stress of W, so forces are exactly -dE/dx for eta = 0.
// Nodal forces: f_a = -V0 P grad_X N_a with P = J sigma F^-T (= -V sigma grad_x N_a), f_0 = -(f_1+f_2+f_3).
//
// Initial (in-situ) stress, optional, per material: a constant second Piola-Kirchhoff stress S0 = sigma0,
// so the Cauchy stress is sigma = sigma_law(F, D) + F S0 F^T / J. An undeformed tet carries sigma0 exactly
// (corner forces -V0 sigma0 grad_X N_a), balanced inside a uniformly prestressed body and at its boundary by
// tractions sigma0 n. The prestress belongs to the material: a rigidly turned tet carries R sigma0 R^T, and
// its forces -V0 F S0 grad_X N_a are exactly minus the gradient of the prestress energy the energy output
// adds,
//   V0 S0 : E,   E = (F^T F - I) / 2  (Green-Lagrange strain),
// so the solid's energy balance holds however far the body turns and strains. (A Cauchy sigma0 held fixed in
// space instead has no potential unless it is hydrostatic: it does work around closed paths that rotate the
// body, and an energy balance that books V0 sigma0 : (F - I) for it drifts once fragments spin.)
//
// Viscous power, optional: P = eta (D:D) V >= 0 (V current volume) [W], the rate of work of the damping
// stress eta D, for the engine to integrate as damping dissipation.
//
// Two implementations of the same law: tet_forces_scalar (one tet at a time, the reference) and
// tet_forces (4 tets per AVX2 register). Both instantiate one templated law body (tet_law.hpp), so
// they differ only in how data is gathered and scattered; tests compare them on random tets.
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

struct TetMaterial {
  double lambda;  // Lamé's first constant [Pa]
  double mu;      // shear modulus [Pa]
  double eta;     // viscous coefficient of the rate-of-deformation term [Pa s]
};

// Reference geometry, once per mesh. For tets [begin, end):
//   dm_inv (9 per tet, row-major) = inverse of F0 = [X1-X0, X2-X0, X3-X0] (columns are edges),
//   volume0 (1 per tet) = det F0 / 6.
// Tets with det F0 <= 0 (or not finite) get volume0 = 0 and dm_inv = 0; tet_forces then skips them.
// Returns how many such tets there were; the caller reports them.
size_t tet_prepare(std::span<const double> x0, std::span<const int32_t> tet_nodes, std::span<double> dm_inv,
                   std::span<double> volume0, size_t begin, size_t end);

struct TetForceArgs {
  std::span<const double> x, v;             // current positions and velocities, 3 per node
  std::span<const int32_t> tet_nodes;       // 4 per tet
  std::span<const double> dm_inv, volume0;  // 9 / 1 per tet, from tet_prepare
  std::span<const int32_t> material;        // 1 per tet, index into materials
  std::span<const TetMaterial> materials;
  std::span<double> corner_force;   // out, 12 per tet: internal force on corners 0..3 (x y z each)
  std::span<double> stress;         // out, 6 per tet: Cauchy xx yy zz xy yz zx; may be empty (skipped)
  std::span<double> strain_energy;  // out, 1 per tet: W(F) V0 (+ prestress energy); may be empty (skipped)
  // Trailing optional members (default empty, so positional initialisers above stay valid):
  std::span<double> viscous_power = {};         // out, 1 per tet: eta (D:D) V [W]; empty = skipped
  std::span<const double> initial_stress = {};  // 6 per material: S0 = sigma0, xx yy zz xy yz zx [Pa];
                                                // empty = none
  // The tet whose corner forces sit at corner_force[0]: tet t writes corner_force[12 (t - first) ...], so a
  // caller can have a range of tets write into a small scratch block (the fused node pass keeps them in L1).
  // The other outputs are indexed by t as it is.
  size_t corner_force_first = 0;
};

// Tets whose current J = det F is not > 0 (inverted, flat or NaN). Their outputs are written as 0.
// Tets with volume0 == 0 (rejected by tet_prepare) also get zeros but are not counted.
struct TetForceStatus {
  size_t inverted = 0;
  int64_t first_inverted = -1;  // lowest such tet index in [begin, end), -1 if none
};

// Outputs are overwritten (not accumulated) for tets [begin, end). Ranges may be split arbitrarily between
// threads; every tet's result is independent of the split (the vector path pads partial groups of 4 by
// repeating the last tet rather than finishing them with scalar code).
TetForceStatus tet_forces_scalar(const TetForceArgs& args, size_t begin, size_t end);
// Fast path: explicit 4-wide AVX2. Without __AVX2__ at compile time it forwards to tet_forces_scalar.
TetForceStatus tet_forces(const TetForceArgs& args, size_t begin, size_t end);
// True when tet_forces was compiled with the AVX2 path (benchmarks and tests report it).
bool tet_forces_vectorised();

}  // namespace rift::kernels
