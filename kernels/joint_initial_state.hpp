#pragma once
// The in-situ state of a joint (femdem.md 1b): the initial offset o0 (JointArgs::initial_offset) for which
// the pre-peak law gives exactly the in-situ traction t0 = sigma0 n on the joint, with no damage.
//
// With k = p / h, op = 2 f_t / k and sigma_n0 = t0.n, tau0 = |t0 - sigma_n0 n| (joint_law.hpp):
//   normal, compression (sigma_n0 <= 0):  o_n = sigma_n0 / k                       (the linear penalty)
//   normal, tension (0 < sigma_n0 < f_t): o_n = op (1 - sqrt(1 - sigma_n0 / f_t))  (inverts f_t (2x - x^2))
//   shear (tau0 < f_s):                   o_s = sp (1 - sqrt(1 - tau0 / f_s)),  sp = 2 f_s / k
// with f_s the Mohr-Coulomb strength at that confinement (c - sigma_n0 tan(phi) in compression, c in
// tension), and o0 = o_n n + o_s t0_s / tau0 along the in-situ shear direction. Both roots are taken on the
// rising branch (x, y < 1), so the point is intact (D = 0) and the law holds t0 there.
#include "kernels/joint_law.hpp"
#include "kernels/softening.hpp"

namespace rift::kernels {

// h: the joint's element size (shortest mid-surface edge, as joint_forces uses); n: its unit normal (from
// side B into side A); traction: t0 = sigma0 n, global frame [Pa]. Writes offset[3] [m].
// Returns false, writing zeros, when the in-situ traction reaches the strength (sigma_n0 >= f_t or
// tau0 >= f_s): the joint cannot hold it, and the caller reports that the in-situ state exceeds the joint
// strength. softening and Z do not enter the pre-peak law; they are taken so the signature matches
// joint_point_response's and a future law with a pre-peak dependence on them needs no new callers.
bool joint_initial_offset(const JointMaterial& m, double h, const double n[3], const double traction[3],
                          Softening softening, double Z, double offset[3]);

}  // namespace rift::kernels
