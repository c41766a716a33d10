#pragma once
// Munjiza's strain-softening curve and the softening lengths of the joint law (femdem.md 1b).
//
//   z(D) = [1 - (a+b-1)/(a+b) exp(D (a + c b) / ((a+b)(1-a-b)))] [a (1-D) + b (1-D)^c],  D in [0, 1]
//   a = 0.63, b = 1.8, c = 6 (Munjiza, Andrews & White 1999; every Y variant), z(0) = 1, z(1) = 0.
//
// Energy per unit area of one mode (strength f, peak separation sp = 2 h f / p, softening length L):
//   pre-peak  (2/3) f sp    (the hardening curve f [2x - x^2], x = separation / sp)
//   softening f L Z,        Z = integral_0^1 z(D) dD = 0.386307...
// Two choices of L (femdem.md 1b, "Energy of the law"):
//   energy_exact: L = (G - (2/3) f sp) / (f Z), so that pre-peak + softening work = G exactly. Needs
//                 G > (2/3) f sp, i.e. p > joint_min_penalty(h, f, G); otherwise L <= 0 and the caller must
//                 refuse the material (the kernel counts such cases and falls back to a brittle drop).
//   y_compatible: L = max(2 sp, 3 G / f), the Y2D/Y3D rule. It assumes Z = 1/3, so with L = 3 G / f the
//                 softening work is 3 Z G = 1.159 G, plus the pre-peak work on top.
#include <cmath>

namespace rift::kernels {

enum class Softening { energy_exact, y_compatible };

// The curve's constants (the exponent factor is negative: z decays).
inline constexpr double kSofteningA = 0.63, kSofteningB = 1.8;
inline constexpr int kSofteningC = 6;

// z(D) for D in [0, 1]. Branch-free, (1-D)^6 by multiplication.
inline double softening_z(double D) {
  constexpr double a = kSofteningA, b = kSofteningB, c = kSofteningC;
  constexpr double lead = (a + b - 1.0) / (a + b);
  constexpr double rate = (a + c * b) / ((a + b) * (1.0 - a - b));
  const double u = 1.0 - D;
  const double u2 = u * u;
  const double u6 = u2 * u2 * u2;
  static_assert(kSofteningC == 6, "u6 above is (1-D)^c");
  return (1.0 - lead * std::exp(rate * D)) * (a * u + b * u6);
}

// Z = integral_0^1 z(D) dD, by composite 5-point Gauss-Legendre on 64 panels (z is an entire function, so
// this is exact to round-off). Computed on first use, then cached.
double softening_integral();

// Softening length L of one mode for strength f, peak separation sp and fracture energy G (see above).
// energy_exact may return L <= 0 (G too small for this penalty and element size): the caller decides.
// Z is softening_integral(), passed in so hot loops do not touch the cached static. For any lane type T
// (the joint law's, kernels/joint_law.hpp) with its max.
template <class T, class Max>
inline T softening_length(Softening rule, T f, T sp, T G, double Z, Max max) {
  if (rule == Softening::y_compatible) return max(2.0 * sp, 3.0 * G / f);
  return (G - (2.0 / 3.0) * f * sp) / (f * Z);
}
inline double softening_length(Softening rule, double f, double sp, double G, double Z) {
  return softening_length(rule, f, sp, G, Z, [](double a, double b) { return std::fmax(a, b); });
}

// Smallest penalty p for which energy_exact has a positive softening length: (2/3) f (2 h f / p) < G
// <=> p > 4 h f^2 / (3 G). The returned value itself is the (excluded) limit. Use the largest h of the mesh
// for mode I (op grows with h), and for mode II the largest shear strength the run can reach (f_s grows
// with confinement under Mohr-Coulomb).
inline double joint_min_penalty(double h, double strength, double G) {
  return 4.0 * h * strength * strength / (3.0 * G);
}

}  // namespace rift::kernels
