#pragma once
// Deterministic assembly from per-element contributions, for loops over elements that run in parallel.
// Element-level work writes each contribution into its own buffer position (no two elements share one),
// then each target (a matrix entry, a node) sums the positions that belong to it in a fixed order. No
// floating-point value is accumulated across threads, and the order is the element order, so the result
// is bitwise the one of a sequential "for each element: target += contribution" loop, on any thread count.
//
// A gather map lists, for target i, the source positions idx[ptr[i]] .. idx[ptr[i + 1] - 1] in ascending
// order; it is the inverse of the "target of each source position" map (e.g. the CSR slot of each of a
// tet's 16 entries, or the node of each of its 4 corners), built once at set-up.
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

// ptr (targets + 1) and idx (target_of.size()) from target_of[source] = target: a stable counting sort,
// so each target's sources come in ascending order. target_of values must lie in [0, targets).
void build_gather_map(std::span<const int32_t> target_of, std::span<int32_t> ptr, std::span<int32_t> idx);

// out[i] = sum_k elem[idx[k]], k over [ptr[i], ptr[i + 1]) in order, for targets [begin, end); written,
// not accumulated. The sum starts from +0.0, as the sequential loop's zeroed target does.
void gather_sum(std::span<const int32_t> ptr, std::span<const int32_t> idx, std::span<const double> elem,
                std::span<double> out, size_t begin, size_t end);

// Three components per source and target: out[3 i + d] = sum_k elem[3 idx[k] + d].
void gather_sum3(std::span<const int32_t> ptr, std::span<const int32_t> idx, std::span<const double> elem,
                 std::span<double> out, size_t begin, size_t end);

}  // namespace rift::kernels
