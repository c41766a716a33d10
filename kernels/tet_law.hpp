#pragma once
// The Y3D tetrahedron law (tet_forces.hpp) written once for an arithmetic type T with + - * /: double
// (the scalar reference) or a 4-wide vector such as __m256d (one tet per lane). Internal to kernels/.
//
// Everything small-strain sensitive is formed from the displacement gradient H = F - I rather than from F,
// so B - I, J - 1 and the energy keep full relative precision down to strains of 1e-12 and below
// (B - I from F F^T would lose all digits under ~1e-8 because of the cancellation against I).
//
// Every function is forced inline: each path instantiates the law twice (with and without an initial
// stress), and gcc then stops inlining it on its own, which cost ~30 % of the throughput.
#include <cmath>

namespace rift::kernels::tet_law {

// Broadcast a constant; each translation unit specialises it for its lane type.
template <class T>
T splat(double a);
template <>
inline double splat<double>(double a) {
  return a;
}

// Voigt order xx yy zz xy yz zx: component n is the tensor's (voigt_row[n], voigt_col[n]).
constexpr int voigt_row[6] = {0, 1, 2, 0, 1, 2}, voigt_col[6] = {0, 1, 2, 1, 2, 0};

template <class T>
struct Kinematics {
  T H[3][3];    // displacement gradient F - I
  T cof[3][3];  // cofactor matrix of F, = J F^-T
  T q;          // I2(H) + det H, the higher-order part of J - 1
  T j;          // J - 1 = tr H + q
  T J;          // det F
};

template <class T>
struct Constants {
  T lambda, mu, eta, volume0;
};

template <class T>
struct Response {
  T force[4][3];  // corner forces
  T stress[6];    // Cauchy xx yy zz xy yz zx, initial stress included
  T energy;       // W V0 (+ the prestress energy), when wanted
  T power;        // viscous power eta (D:D) V, when wanted
};

// The optional parts of the response: what the caller will store, and the initial stress if any. Outputs
// are runtime flags evaluated after the forces, so asking for them cannot change a bit of the forces (one
// compiled law, whatever is stored). Callers make sigma0 a compile-time null when there is no initial stress,
// so that path compiles to the law without it.
template <class T>
struct Wanted {
  bool energy = false, power = false;
  const T* sigma0 = nullptr;  // 6 components (Voigt order as the stress), or none
};

// Edge vectors e[c] = p[c+1] - p[0] of the corner positions or velocities p.
template <class T>
[[gnu::always_inline]] inline void edges(const T p[4][3], T e[3][3]) {
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) e[c][i] = p[c + 1][i] - p[0][i];
}

// G = E Dm with E's columns the edges e[c] (position edges give F, velocity edges F-dot).
template <class T>
[[gnu::always_inline]] inline void edge_gradient(const T e[3][3], const T dm[9], T G[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) G[i][k] = e[0][i] * dm[k] + e[1][i] * dm[3 + k] + e[2][i] * dm[6 + k];
}

template <class T>
[[gnu::always_inline]] inline void cofactors(const T A[3][3], T C[3][3]) {
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      C[i][k] = A[i1][k1] * A[i2][k2] - A[i1][k2] * A[i2][k1];
    }
  }
}

// H, cof(F) and J from the position edges ex, all through H (F itself is never formed):
//   J - 1 = tr H + I2(H) + det H,   cof(I + H) = (1 + tr H) I - H^T + cof(H),
// each term free of cancellation, and cof(H) serves both.
template <class T>
[[gnu::always_inline]] inline void kinematics(const T ex[3][3], const T dm[9], Kinematics<T>& k) {
  const T one = splat<T>(1.0);
  edge_gradient(ex, dm, k.H);
  for (int i = 0; i < 3; ++i) k.H[i][i] = k.H[i][i] - one;
  T cH[3][3];
  cofactors(k.H, cH);
  const T det_h = k.H[0][0] * cH[0][0] + k.H[0][1] * cH[0][1] + k.H[0][2] * cH[0][2];
  const T i2 = cH[0][0] + cH[1][1] + cH[2][2];  // sum of the principal 2x2 minors
  const T tr_h = k.H[0][0] + k.H[1][1] + k.H[2][2];
  k.q = i2 + det_h;
  k.j = tr_h + k.q;
  k.J = one + k.j;
  for (int i = 0; i < 3; ++i)
    for (int m = 0; m < 3; ++m) k.cof[i][m] = cH[i][m] - k.H[m][i];
  for (int i = 0; i < 3; ++i) k.cof[i][i] = k.cof[i][i] + (one + tr_h);
}

// j - ln(1 + j) by its Taylor series, for |j| < small_j: the omitted term is < 2|j|^9/11 relative (< 2e-19).
// Larger |j| use j - log1p(j) directly (cancellation then costs at most a factor 2/|j| = 200).
constexpr double small_j = 0.01;
// j^2 (1/2 - j/3 + j^2/4 - ... + j^8/10), the polynomial evaluated in Estrin's form (pairs, then pairs of
// pairs) so its dependency chain is 4 multiply-adds long instead of 9.
template <class T>
[[gnu::always_inline]] inline T excess_log_series(T j) {
  auto c = [](int n) { return splat<T>((n % 2 ? -1.0 : 1.0) / (n + 2)); };  // coefficient of j^n
  const T j2 = j * j, j4 = j2 * j2;
  const T p01 = c(0) + c(1) * j, p23 = c(2) + c(3) * j, p45 = c(4) + c(5) * j, p67 = c(6) + c(7) * j;
  const T p03 = p01 + p23 * j2, p47 = p45 + p67 * j2;
  const T p8 = c(8) * j4;
  return j2 * (p03 + (p47 + p8) * j4);
}
[[gnu::always_inline]] inline double excess_log(double j) {
  return std::fabs(j) < small_j ? excess_log_series(j) : j - std::log1p(j);
}

// Cauchy stress sigma = (mu/J)(B - I) + (lambda/2)(J - 1/J) I + eta D, with B - I = H + H^T + H H^T,
// J - 1/J = j (2 + j) / J and D = sym(F-dot F^-1) = sym(F-dot cof^T) / J. two_d receives 2 J D (Voigt
// order) for the viscous power.
template <class T>
[[gnu::always_inline]] inline void cauchy_stress(const Kinematics<T>& k, const T Fdot[3][3],
                                                 const Constants<T>& c, T s[6], T two_d[6]) {
  const T inv_j = splat<T>(1.0) / k.J;
  const T shear = c.mu * inv_j;
  const T volumetric = splat<T>(0.5) * c.lambda * k.j * (splat<T>(2.0) + k.j) * inv_j;
  const T half_visc = splat<T>(0.5) * c.eta * inv_j;
  auto l = [&](int a, int b) {  // (F-dot cof^T)_ab = J L_ab
    return Fdot[a][0] * k.cof[b][0] + Fdot[a][1] * k.cof[b][1] + Fdot[a][2] * k.cof[b][2];
  };
  for (int n = 0; n < 6; ++n) {
    const int a = voigt_row[n], b = voigt_col[n];
    const T bm =
        k.H[a][b] + k.H[b][a] + (k.H[a][0] * k.H[b][0] + k.H[a][1] * k.H[b][1] + k.H[a][2] * k.H[b][2]);
    two_d[n] = l(a, b) + l(b, a);  // 2 J D_ab
    s[n] = shear * bm + half_visc * two_d[n];
    if (a == b) s[n] = s[n] + volumetric;
  }
}

// f_a = -V0 P grad_X N_a, P = sigma cof(F) (first Piola), grad_X N_a = row a-1 of Dm; f_0 balances.
template <class T>
[[gnu::always_inline]] inline void corner_forces(const Kinematics<T>& k, const T s[6], const T dm[9],
                                                 T volume0, T f[4][3]) {
  const T sig[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  T P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int m = 0; m < 3; ++m)
      P[i][m] = sig[i][0] * k.cof[0][m] + sig[i][1] * k.cof[1][m] + sig[i][2] * k.cof[2][m];
  const T scale = splat<T>(0.0) - volume0;
  for (int i = 0; i < 3; ++i) {
    for (int a = 1; a < 4; ++a) {
      const T* g = dm + 3 * (a - 1);
      f[a][i] = scale * (P[i][0] * g[0] + P[i][1] * g[1] + P[i][2] * g[2]);
    }
    f[0][i] = splat<T>(0.0) - (f[1][i] + f[2][i] + f[3][i]);
  }
}

// W V0 with W = mu/2 (|H|^2 - 2q + 2g) + lambda/4 (j^2 + 2g), g = j - ln J: the same W as in
// tet_forces.hpp, rearranged using tr C - 3 = |H|^2 + 2 tr H and tr H - j = -q.
template <class T>
[[gnu::always_inline]] inline T strain_energy(const Kinematics<T>& k, T g, const Constants<T>& c) {
  T h2 = splat<T>(0.0);
  for (int i = 0; i < 3; ++i)
    for (int m = 0; m < 3; ++m) h2 = h2 + k.H[i][m] * k.H[i][m];
  const T two = splat<T>(2.0);
  const T w =
      splat<T>(0.5) * c.mu * (h2 - two * k.q + two * g) + splat<T>(0.25) * c.lambda * (k.j * k.j + two * g);
  return w * c.volume0;
}

// The initial stress is a constant second Piola-Kirchhoff stress S0 (tet_forces.hpp). Its Cauchy stress
// F S0 F^T / J, added to s, formed through H so that H = 0 gives S0 exactly:
//   F S0 F^T = S0 + M + M^T + M H^T,  M = H S0.
template <class T>
[[gnu::always_inline]] inline void add_prestress(const Kinematics<T>& k, const T s0[6], T s[6]) {
  const T S[3][3] = {{s0[0], s0[3], s0[5]}, {s0[3], s0[1], s0[4]}, {s0[5], s0[4], s0[2]}};
  T M[3][3];
  for (int i = 0; i < 3; ++i)
    for (int m = 0; m < 3; ++m) M[i][m] = k.H[i][0] * S[0][m] + k.H[i][1] * S[1][m] + k.H[i][2] * S[2][m];
  const T inv_j = splat<T>(1.0) / k.J;
  for (int n = 0; n < 6; ++n) {
    const int a = voigt_row[n], b = voigt_col[n];
    const T push = M[a][b] + M[b][a] + (M[a][0] * k.H[b][0] + M[a][1] * k.H[b][1] + M[a][2] * k.H[b][2]);
    s[n] = s[n] + (s0[n] + push) * inv_j;
  }
}

// V0 S0 : E, E = (F^T F - I) / 2 = (H + H^T + H^T H) / 2: the exact potential of the prestress forces
// -V0 F S0 grad_X N_a (tet_forces.hpp). S0 symmetric, so S0 : (H + H^T) / 2 = S0 : H.
template <class T>
[[gnu::always_inline]] inline T prestress_energy(const Kinematics<T>& k, const T s0[6], T volume0) {
  T e = splat<T>(0.0);
  for (int n = 0; n < 6; ++n) {
    const int a = voigt_row[n], b = voigt_col[n];
    const T hth = k.H[0][a] * k.H[0][b] + k.H[1][a] * k.H[1][b] + k.H[2][a] * k.H[2][b];     // (H^T H)_ab
    const T green = a == b ? k.H[a][a] + splat<T>(0.5) * hth : k.H[a][b] + k.H[b][a] + hth;  // E_ab (x2 off)
    e = e + s0[n] * green;
  }
  return e * volume0;
}

// eta (D:D) V with D = two_d / (2 J) and V = J V0: eta V0 (sum of two_d^2, off-diagonal twice) / (4 J).
// A sum of squares, so >= 0 whatever the rounding.
template <class T>
[[gnu::always_inline]] inline T viscous_power(const T two_d[6], T J, const Constants<T>& c) {
  const T diagonal = two_d[0] * two_d[0] + two_d[1] * two_d[1] + two_d[2] * two_d[2];
  const T off = two_d[3] * two_d[3] + two_d[4] * two_d[4] + two_d[5] * two_d[5];
  return splat<T>(0.25) * c.eta * c.volume0 * (diagonal + splat<T>(2.0) * off) / J;
}

// Everything after the kinematics (ev: velocity edges); the caller has checked J > 0 (lanes where it is not
// are discarded). g = j - ln J for the energy (ignored unless want.energy).
template <class T>
[[gnu::always_inline]] inline void response(const Kinematics<T>& k, const T ev[3][3], const T dm[9],
                                            const Constants<T>& c, T g, const Wanted<T>& want,
                                            Response<T>& r) {
  T Fdot[3][3], two_d[6];
  edge_gradient(ev, dm, Fdot);
  cauchy_stress(k, Fdot, c, r.stress, two_d);
  if (want.sigma0) add_prestress(k, want.sigma0, r.stress);
  corner_forces(k, r.stress, dm, c.volume0, r.force);
  if (want.energy) {
    r.energy = strain_energy(k, g, c);
    if (want.sigma0) r.energy = r.energy + prestress_energy(k, want.sigma0, c.volume0);
  }
  if (want.power) r.power = viscous_power(two_d, k.J, c);
}

}  // namespace rift::kernels::tet_law
