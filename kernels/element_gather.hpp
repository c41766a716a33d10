#pragma once
// Deterministic assembly from per-element contributions, for loops over elements that run in parallel.
// Element-level work writes each contribution into its own buffer position (no two elements share one),
// then each target (a matrix entry, a node) sums the positions that belong to it in a fixed order. No
// floating-point value is accumulated across threads, and the order is the element order, so the result
// is bitwise the one of a sequential "for each element: target += contribution" loop, on any thread count.
//
// The buffer is sorted by target: the contributions of target i sit at positions ptr[i] .. ptr[i + 1] - 1
// in ascending order of their source (the element-local position, e.g. 16 t + 4 a + b for tet t's entry
// (a, b), or 4 t + a for its corner a), and pos[source] says where. The element pass therefore scatters
// its writes (fire and forget) and the gather streams through the buffer instead of chasing sources.
// Both maps are built once at set-up from "the target of each source" (the CSR slot of each entry, the
// node of each corner).
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

// ptr (targets + 1) and pos (target_of.size()) from target_of[source] = target: a stable counting sort,
// so each target's sources come in ascending order. target_of values must lie in [0, targets).
void build_gather_positions(std::span<const int32_t> target_of, std::span<int32_t> ptr,
                            std::span<int32_t> pos);

// out[i] = sum of elem[ptr[i]] .. elem[ptr[i + 1] - 1] in order, for targets [begin, end); written, not
// accumulated. The sum starts from +0.0, as the sequential loop's zeroed target does.
void gather_sum(std::span<const int32_t> ptr, std::span<const double> elem, std::span<double> out,
                size_t begin, size_t end);

// Three components per position and target: out[3 i + d] = sum_k elem[3 k + d].
void gather_sum3(std::span<const int32_t> ptr, std::span<const double> elem, std::span<double> out,
                 size_t begin, size_t end);

}  // namespace rift::kernels
