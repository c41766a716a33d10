#include "engine/mesh/graded_axis.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace rift {
namespace {

constexpr double kMaxCells = 1e7;  // along one axis: far beyond any budget, short of overflow

// Cells from the fine zone's end outward over `length`: size * growth, size * growth^2, ..., each at most
// max_size, and then the rest, which is between half and one and a half of the cell it replaces.
// visit(cell length) for each; returns the count.
template <class Visit>
size_t outward_cells(double length, double size, double growth, double max_size, Visit&& visit) {
  if (length <= 0.0) return 0;
  double covered = 0.0, h = std::min(size * growth, max_size);
  for (size_t count = 0;; ++count) {
    const double next = std::min(h * growth, max_size);
    if (covered + h + 0.5 * next > length) {
      visit(length - covered);
      return count + 1;
    }
    if (count > kMaxCells) throw Error("graded lattice: more than 1e7 cells along one axis");
    visit(h);
    covered += h;
    h = next;
  }
}

// The fine interval clipped to the box, snapped to its ends when within a billionth of a cell.
std::pair<double, double> fine_interval(double lo, double hi, double fine_lo, double fine_hi, double size,
                                        double growth, double max_size) {
  if (!(lo < hi) || !(fine_lo < fine_hi) || !(size > 0.0) || !(growth >= 1.0) || fine_hi <= lo ||
      fine_lo >= hi || !(max_size >= size))
    throw Error(
        "graded lattice: expected lo < hi, a fine interval overlapping it, size > 0, growth >= 1 and "
        "max_size >= size");
  double a = std::max(lo, fine_lo), b = std::min(hi, fine_hi);
  if (a - lo < 1e-9 * size) a = lo;
  if (hi - b < 1e-9 * size) b = hi;
  if ((b - a) / size > kMaxCells) throw Error("graded lattice: more than 1e7 fine cells along one axis");
  return {a, b};
}

int fine_cells(double a, double b, double size) {
  return static_cast<int>(std::max(1.0, std::round((b - a) / size)));
}

}  // namespace

size_t graded_axis_nodes(double lo, double hi, double fine_lo, double fine_hi, double size, double growth,
                         double max_size) {
  const auto [a, b] = fine_interval(lo, hi, fine_lo, fine_hi, size, growth, max_size);
  auto ignore = [](double) {};
  return static_cast<size_t>(fine_cells(a, b, size)) + 1 +
         outward_cells(a - lo, size, growth, max_size, ignore) +
         outward_cells(hi - b, size, growth, max_size, ignore);
}

std::vector<double> graded_axis(double lo, double hi, double fine_lo, double fine_hi, double size,
                                double growth, double max_size) {
  const auto [a, b] = fine_interval(lo, hi, fine_lo, fine_hi, size, growth, max_size);
  std::vector<double> x;
  x.reserve(graded_axis_nodes(lo, hi, fine_lo, fine_hi, size, growth, max_size));
  double p = a;
  outward_cells(a - lo, size, growth, max_size, [&](double h) { x.push_back(p -= h); });  // a - h1, ...
  if (!x.empty()) x.back() = lo;
  std::reverse(x.begin(), x.end());
  const int n = fine_cells(a, b, size);
  for (int i = 0; i <= n; ++i) x.push_back(i == n ? b : a + (b - a) * i / n);
  const size_t fine_end = x.size();
  p = b;
  outward_cells(hi - b, size, growth, max_size, [&](double h) { x.push_back(p += h); });
  if (x.size() > fine_end) x.back() = hi;
  return x;
}

Axes graded_lattice_axes(const std::array<double, 3>& origin, const std::array<double, 3>& extent,
                         const std::array<double, 3>& fine_min, const std::array<double, 3>& fine_max,
                         double size, double growth) {
  Axes axes;
  for (int d = 0; d < 3; ++d)
    axes[d] = graded_axis(origin[d], origin[d] + extent[d], fine_min[d], fine_max[d], size, growth);
  return axes;
}

std::array<size_t, 3> graded_lattice_nodes(const std::array<double, 3>& origin,
                                           const std::array<double, 3>& extent,
                                           const std::array<double, 3>& fine_min,
                                           const std::array<double, 3>& fine_max, double size,
                                           double growth) {
  std::array<size_t, 3> n{};
  for (int d = 0; d < 3; ++d)
    n[d] = graded_axis_nodes(origin[d], origin[d] + extent[d], fine_min[d], fine_max[d], size, growth);
  return n;
}

}  // namespace rift
