#pragma once
// A sum whose bits do not depend on the order of its terms or on how they are split (between threads,
// between processes): pre-rounding to a power-of-two grid (Rump, Ogita and Oishi, "Accurate floating-point
// summation", SIAM J. Sci. Comput. 31, 2008; Demmel and Nguyen, "Parallel reproducible summation", IEEE
// Trans. Comput. 64, 2015).
//
// With sigma = 1.5 x 2^e and |x| <= 2^(e-1), fl(sigma + x) lies in [2^e, 2^(e+1)), so fl(sigma + x) - sigma
// is x rounded to a multiple of g = 2^(e-52), exactly, whatever else is being summed. Multiples of g
// add exactly while their partial sums stay below 2^53 g = 2^(e+1): with 2^e >= 2 n max|x| for n terms,
// every partial sum does, in any order. The remainders x - q (|r| <= g/2, also exact) get a second grid
// chosen the same way, which brings the result to about double accuracy; the result is the two exact sums
// added once. Partial sums made from the same grid merge exactly (operator+=, or MPI_SUM).
//
// The grid needs the count and a bound on |x| before the sum: every part of a split must use the same
// ones (a maximum is itself order-free). A term beyond the bound is counted in `exceeded`, and the sum must
// then be redone on a wider grid.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

struct ReproducibleGrid {
  double bound = 0.0;   // largest |x| the grid takes
  double sigma1 = 0.0;  // 1.5 x 2^e1, 2^e1 >= 2 n bound
  double sigma2 = 0.0;  // 1.5 x 2^e2, 2^e2 >= n g1 (g1 = 2^(e1 - 52), the remainders' bound g1 / 2 doubled)
};

// The grid for `count` terms of |x| <= max_abs. A bound of 0 (all terms 0) or beyond what doubles can grid
// (count max_abs above 2^1000) gives a grid with bound 0, which counts every non-zero term as exceeded.
inline ReproducibleGrid reproducible_grid(double max_abs, int64_t count) {
  ReproducibleGrid g;
  if (!(max_abs > 0.0) || count < 1 || !std::isfinite(max_abs)) return g;
  const double span = 2.0 * double(count) * max_abs;  // 2^e1 must reach it
  if (!(span < std::ldexp(1.0, 1000))) return g;
  const int e1 = std::ilogb(span) + 1;  // 2^e1 > span
  const int e2 = std::max(e1 - 52 + std::ilogb(double(count)) + 1, -1020);
  g.bound = max_abs;
  g.sigma1 = 1.5 * std::ldexp(1.0, e1);
  g.sigma2 = 1.5 * std::ldexp(1.0, e2);
  return g;
}

struct ReproducibleSum {
  double first = 0.0, second = 0.0;  // exact sums of the terms on the first and the second grid
  int64_t exceeded = 0;              // terms beyond the grid's bound: the sum is not reproducible

  // (sigma + x) - sigma is a rounding on purpose: the build never lets the compiler reassociate it (no
  // -ffast-math), and with no product in it there is nothing to contract into an FMA.
  void add(double x, const ReproducibleGrid& g) {
    if (!(std::abs(x) <= g.bound) && x != 0.0) ++exceeded;
    const double q1 = (g.sigma1 + x) - g.sigma1;
    const double q2 = (g.sigma2 + (x - q1)) - g.sigma2;
    first += q1;
    second += q2;
  }
  ReproducibleSum& operator+=(const ReproducibleSum& o) {
    first += o.first;
    second += o.second;
    exceeded += o.exceeded;
    return *this;
  }
  double value() const { return first + second; }
};

// The order-free sum of n terms that are all at hand (a column, or one partial sum per fixed unit of work):
// their largest magnitude first, then the sum on the grid it gives, so nothing is carried from one call to
// the next. term(i) must return the same value both times it is called. A non-finite term makes the
// result non-finite.
template <class Term>
double reproducible_total(size_t n, Term&& term) {
  double max_abs = 0.0;
  for (size_t i = 0; i < n; ++i) max_abs = std::max(max_abs, std::abs(term(i)));
  const ReproducibleGrid grid = reproducible_grid(max_abs, static_cast<int64_t>(n));
  ReproducibleSum sum;
  for (size_t i = 0; i < n; ++i) sum.add(term(i), grid);
  return sum.value();
}

inline double reproducible_total(std::span<const double> terms) {
  return reproducible_total(terms.size(), [&](size_t i) { return terms[i]; });
}

}  // namespace rift::kernels
