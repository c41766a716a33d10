// kernels/reproducible_sum.hpp: the same bits in any order and any split, against a sum in binary128
// (GCC's __float128: 113 bits, exact enough to judge a double sum).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "kernels/reproducible_sum.hpp"

namespace rift::kernels {
namespace {

uint64_t bits(double x) {
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Terms of mixed sign over 13 decades, as energy increments of very different elements are.
std::vector<double> mixed_terms(size_t n, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0), decade(-10.0, 3.0);
  std::vector<double> x(n);
  for (double& v : x) v = mantissa(rng) * std::pow(10.0, decade(rng));
  return x;
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}

// The sum of x split into `parts` pieces at random cuts, each summed on its own, merged in random order.
double split_sum(const std::vector<double>& x, const ReproducibleGrid& g, int parts, std::mt19937& rng) {
  std::vector<size_t> cuts{0, x.size()};
  for (int p = 1; p < parts; ++p) cuts.push_back(rng() % x.size());
  std::sort(cuts.begin(), cuts.end());
  std::vector<ReproducibleSum> pieces(cuts.size() - 1);
  for (size_t p = 0; p + 1 < cuts.size(); ++p)
    for (size_t i = cuts[p]; i < cuts[p + 1]; ++i) pieces[p].add(x[i], g);
  std::shuffle(pieces.begin(), pieces.end(), rng);
  ReproducibleSum total;
  for (const auto& p : pieces) total += p;
  EXPECT_EQ(total.exceeded, 0);
  return total.value();
}

TEST(ReproducibleSum, AnyOrderAndAnySplitGiveTheSameBitsWhereAPlainSumDoesNot) {
  std::vector<double> x = mixed_terms(100000, 3);
  const ReproducibleGrid g = reproducible_grid(max_abs(x), int64_t(x.size()));
  std::mt19937 rng(5);
  const double first = split_sum(x, g, 1, rng);
  const double plain_first = std::accumulate(x.begin(), x.end(), 0.0);
  bool plain_differs = false;
  for (int round = 0; round < 8; ++round) {
    std::shuffle(x.begin(), x.end(), rng);
    for (int parts : {1, 2, 3, 8, 64}) EXPECT_EQ(bits(split_sum(x, g, parts, rng)), bits(first)) << parts;
    plain_differs |= bits(std::accumulate(x.begin(), x.end(), 0.0)) != bits(plain_first);
  }
  EXPECT_TRUE(plain_differs) << "the terms are too tame to show what the reproducible sum is for";
}

TEST(ReproducibleSum, ItIsAccurateToTheSecondGridAgainstBinary128) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<double> x = mixed_terms(50000, seed);
    const ReproducibleGrid g = reproducible_grid(max_abs(x), int64_t(x.size()));
    ReproducibleSum s;
    __float128 exact = 0;
    for (double v : x) {
      s.add(v, g);
      exact += v;
    }
    // What the second grid drops (half its spacing per term, n terms) and the one final rounding.
    const double g2 = g.sigma2 / 1.5 * std::ldexp(1.0, -52);
    const double allowed = double(x.size()) * 0.5 * g2 + std::abs(double(exact)) * std::ldexp(1.0, -53);
    EXPECT_LE(std::abs(double(__float128(s.value()) - exact)), allowed) << "seed " << seed;
    EXPECT_LT(allowed, 1e-12 * max_abs(x));  // about double accuracy against the largest term
  }
}

TEST(ReproducibleSum, CancellingTermsLeaveTheSmallOneInEveryOrder) {
  // 1e3 and -1e3 in any order around 1e-10: a plain sum keeps the small term only in some orders.
  std::vector<double> x{1e3, 1e-10, -1e3};
  const ReproducibleGrid g = reproducible_grid(1e3, 3);
  for (int order = 0; order < 6; ++order) {
    ReproducibleSum s;
    for (double v : x) s.add(v, g);
    EXPECT_NEAR(s.value(), 1e-10, 3 * 0.5 * g.sigma2 / 1.5 * std::ldexp(1.0, -52));
    std::next_permutation(x.begin(), x.end());
  }
}

TEST(ReproducibleSum, TermsBeyondTheBoundAreCountedAndZerosNever) {
  const ReproducibleGrid g = reproducible_grid(1.0, 10);
  ReproducibleSum s;
  s.add(0.5, g);
  s.add(-1.0, g);
  s.add(0.0, g);
  EXPECT_EQ(s.exceeded, 0);
  s.add(2.0, g);
  EXPECT_EQ(s.exceeded, 1);
  const ReproducibleGrid none = reproducible_grid(0.0, 10);  // every term zero: nothing else fits
  ReproducibleSum z;
  z.add(0.0, none);
  z.add(-0.0, none);
  EXPECT_EQ(z.exceeded, 0);
  EXPECT_EQ(z.value(), 0.0);
  z.add(1e-300, none);
  EXPECT_EQ(z.exceeded, 1);
  EXPECT_EQ(reproducible_grid(1e300, 1 << 20).bound, 0.0);  // beyond what a grid of doubles spans
  EXPECT_EQ(reproducible_grid(std::nan(""), 5).bound, 0.0);
}

TEST(ReproducibleTotal, TermsAtHandSumToOneBitPatternInAnyOrderWithNoBoundGiven) {
  std::vector<double> x = mixed_terms(20000, 11);
  auto total = [&] { return reproducible_total(x.size(), [&](size_t i) { return x[i]; }); };
  const double first = total();
  std::mt19937 rng(2);
  for (int round = 0; round < 6; ++round) {
    std::shuffle(x.begin(), x.end(), rng);
    EXPECT_EQ(bits(total()), bits(first));
  }
  // The same as a split sum on the grid of the same bound: the total is that sum, not another rounding.
  const ReproducibleGrid g = reproducible_grid(max_abs(x), int64_t(x.size()));
  EXPECT_EQ(bits(split_sum(x, g, 3, rng)), bits(first));
  EXPECT_EQ(reproducible_total(0, [](size_t) { return 1.0; }), 0.0);
  const std::vector<double> zeros(5, 0.0);
  EXPECT_EQ(reproducible_total(zeros.size(), [&](size_t i) { return zeros[i]; }), 0.0);
}

TEST(ReproducibleTotal, ANonFiniteTermMakesTheTotalNonFinite) {
  for (double bad : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    std::vector<double> x{1.0, -2.0, bad, 3.0};
    EXPECT_FALSE(std::isfinite(reproducible_total(x.size(), [&](size_t i) { return x[i]; }))) << bad;
  }
}

}  // namespace
}  // namespace rift::kernels
