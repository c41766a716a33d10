#pragma once
// The one gather of the producers whose forces reach the solid's nodes as node rows
// (systems/node_force_route.hpp): contact pairs, the fluid's coupling pairs, the faces of broken joints.
// Each adds its corners' values into a row per node, serially, corner by corner in the producer's own
// fixed order, so a node's sum is the same sequence of additions on any number of threads. (A corner list
// that changes every step has no slots fixed at set-up for the node pass to gather from in parallel.)
#include <cstddef>
#include <span>

namespace rift::kernels {

// For k in [0, corners), in order: out[M node_of(k) + d] += scale * value_of(k)[d] for d < M, where
// node_of(k) is a node index and value_of(k) points at the corner's M values. A scale of 1 adds the values
// exactly as they are (1 x v is v, fused or not).
template <size_t M, class NodeOf, class ValueOf>
inline void add_corners_to_nodes(size_t corners, NodeOf node_of, ValueOf value_of, double scale,
                                 std::span<double> out) {
  for (size_t k = 0; k < corners; ++k) {
    double* to = out.data() + M * static_cast<size_t>(node_of(k));
    const double* from = value_of(k);
    for (size_t d = 0; d < M; ++d) to[d] += scale * from[d];
  }
}

}  // namespace rift::kernels
