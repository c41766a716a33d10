#pragma once
// The node coordinates along one axis of a graded lattice: cells of `size` in the fine interval, growing
// by `growth` per cell away from it on both sides until the box's ends. Where fracture needs small
// elements (a starter crack and the plane it grows in) and the far field only needs to carry the
// elastic response, this keeps the tet count to a few times the fine zone's.
//
// The fine interval [fine_lo, fine_hi] (clipped to the box) is cut into round(length / size) equal cells,
// so that its ends and every multiple of the spacing from fine_lo are nodes: a crack plane at one of them
// is a lattice plane. Outside, the k-th cell is size * growth^k long, at most max_size (default: no cap,
// for a far field that only carries the elastic response; a flow's wake needs the cap); the last cell
// before an end is stretched to reach it exactly when the remainder is less than half a cell, else the
// remainder is a cell of its own. The first and last coordinates are lo and hi exactly.
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace rift {

// Node count along an axis, without building it (for budgets); the same count graded_axis returns.
size_t graded_axis_nodes(double lo, double hi, double fine_lo, double fine_hi, double size, double growth,
                         double max_size = std::numeric_limits<double>::infinity());

// Requires lo < hi, fine_lo < fine_hi overlapping (lo, hi), size > 0, growth >= 1, max_size >= size (the
// scene reader checks these); throws rift::Error otherwise.
std::vector<double> graded_axis(double lo, double hi, double fine_lo, double fine_hi, double size,
                                double growth, double max_size = std::numeric_limits<double>::infinity());

// The three axes of a box [origin, origin + extent] graded from the fine box [fine_min, fine_max], and
// their node counts alone.
using Axes = std::array<std::vector<double>, 3>;
Axes graded_lattice_axes(const std::array<double, 3>& origin, const std::array<double, 3>& extent,
                         const std::array<double, 3>& fine_min, const std::array<double, 3>& fine_max,
                         double size, double growth);
std::array<size_t, 3> graded_lattice_nodes(const std::array<double, 3>& origin,
                                           const std::array<double, 3>& extent,
                                           const std::array<double, 3>& fine_min,
                                           const std::array<double, 3>& fine_max, double size, double growth);

}  // namespace rift
