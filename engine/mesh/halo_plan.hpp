#pragma once
// Who computes what when a run's nodes are split between processes, and what the processes must exchange:
// the owner-computes rule. Each node belongs to one part, the part of the first tet that holds it; where
// nodes come in units (the node pass's energy sums add a unit's terms in a row, so one part must integrate
// a whole unit), each node belongs to the part that holds most of its unit's nodes by that rule. A part
// computes every element with at least one node of its own, so an element across a part boundary is
// computed by every part it touches, redundantly and from the same inputs, hence with the same result, and
// each part gathers its own nodes' forces in the same order as one process does. The nodes of those
// elements that another part owns are the part's ghosts: their state is received once per solid step,
// before the forces.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rift {

// One kind of element that acts on the nodes, e.g. the solid's tets (4 nodes) or joints (6 nodes).
struct ElementNodes {
  std::string name;
  int32_t width = 0;               // nodes per element
  std::span<const int32_t> nodes;  // element e's nodes: nodes[width e] .. nodes[width e + width - 1]
  int32_t weight = 1;              // work units to compute one element for one step
};

// What a model contributes to splitting a run (Model::partition_work), one per mesh it computes on (the
// solid's, the fluid's): the tets as the partitioner sees them (their continuous mesh, whose shared faces
// make the dual graph), the work of each tet for the partitioner (its own and its share of the elements
// around it), the elements computed on the nodes (the first set is the tets, in the same order), and the
// bytes of a node's state a ghost receives at each exchange. `timed`: the work is in units of 25 ns of one
// core a step (docs/performance.md, "Beyond one machine"), so a time per step can be predicted from it.
struct PartitionWork {
  std::string domain;
  std::vector<std::array<int32_t, 4>> graph_tets;
  std::vector<int32_t> tet_weight;
  int32_t nodes = 0;
  int32_t node_bytes = 0;
  bool timed = false;
  std::vector<ElementNodes> elements;
  std::vector<int32_t> node_units;  // the first node of each unit, ascending from 0 (empty: every node alone)
};

struct PartHalo {
  int64_t owned_nodes = 0;
  int64_t ghost_nodes = 0;        // other parts' nodes this part reads every step
  int64_t nodes_sent = 0;         // own nodes that other parts read, counted once per reading part
  int32_t receives_from = 0;      // parts this part receives from (messages per exchange)
  int32_t sends_to = 0;           // parts this part sends to
  std::vector<int64_t> computed;  // per element set: the elements this part computes
  std::vector<int64_t> shared;    // per element set: of those, the ones other parts compute too
  int64_t work = 0;               // the computed elements' weights
};

struct HaloPlan {
  std::vector<std::string> element_sets;
  std::vector<PartHalo> parts;
};

// One part's side of the plan: the lists its loops and its exchange need, all global ids in ascending order.
// What a part receives from a neighbour and what that neighbour sends it are the same list, built by each
// side from the same global mesh, so no list has to be agreed on at run time. Every element across a part
// boundary has own nodes on each part that computes it, so the neighbours a part receives from are the
// ones it sends to.
struct RankHalo {
  int32_t rank = 0;
  std::vector<int32_t> owned;                  // the part's own nodes
  std::vector<int32_t> neighbours;             // the parts it exchanges with
  std::vector<std::vector<int32_t>> receive;   // per neighbour: that neighbour's nodes this part reads
  std::vector<std::vector<int32_t>> send;      // per neighbour: own nodes that neighbour reads
  std::vector<std::vector<int32_t>> elements;  // per element set: the elements this part computes
};

// The part that owns each node by the rule above; `tet_part` and `node_units` as plan_halo's, the same
// errors.
std::vector<int32_t> node_owners(int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                                 std::span<const ElementNodes> sets,
                                 std::span<const int32_t> node_units = {});
// The part that counts each element of a set: the owner of its first node. Every part that computes an
// element holds the same values for it, and this one part counts it where the ranks' results are combined
// (sums over elements, the fracture log, rank 0's copy for outputs). Throws Error on a node out of range.
std::vector<int32_t> element_owners(const ElementNodes& set, std::span<const int32_t> node_owner);

// `tet_part` gives the part of each element of sets[0] (the tets); `node_units` as PartitionWork's. Throws
// Error when a node lies in no tet, an element's node or a part is out of range, an element has more than
// 16 nodes, or the units do not start at node 0 and ascend within the nodes.
HaloPlan plan_halo(int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                   std::span<const ElementNodes> sets, std::span<const int32_t> node_units = {});
// The same plan as seen by `rank` alone, with its lists; the same errors.
RankHalo rank_halo(int32_t rank, int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                   std::span<const ElementNodes> sets, std::span<const int32_t> node_units = {});

}  // namespace rift
