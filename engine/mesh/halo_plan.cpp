#include "engine/mesh/halo_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <utility>

#include "engine/core/error.hpp"

namespace rift {
namespace {

constexpr int32_t kMaxWidth = 16;

// Every node of a unit takes the owner most of the unit's nodes have (the lowest part on a tie).
void own_by_unit(std::vector<int32_t>& owner, std::span<const int32_t> node_units) {
  if (node_units.empty()) return;
  if (node_units[0] != 0)
    throw Error(fmt::format("halo plan: the first node unit starts at node {}, not 0", node_units[0]));
  for (size_t u = 0; u < node_units.size(); ++u) {
    const int32_t end = u + 1 < node_units.size() ? node_units[u + 1] : int32_t(owner.size());
    if (end <= node_units[u] || end > int32_t(owner.size()))
      throw Error(fmt::format("halo plan: node unit {} spans nodes [{}, {}) of {}", u, node_units[u], end,
                              owner.size()));
    // The part holding most of the unit's nodes (the lowest such part on a tie): fewest nodes move.
    int32_t best = owner[size_t(node_units[u])], best_count = 0;
    for (int32_t n = node_units[u]; n < end; ++n) {
      const int32_t candidate = owner[size_t(n)];
      const auto count = int32_t(std::count(owner.begin() + node_units[u], owner.begin() + end, candidate));
      if (count > best_count || (count == best_count && candidate < best)) {
        best = candidate;
        best_count = count;
      }
    }
    std::fill(owner.begin() + node_units[u], owner.begin() + end, best);
  }
}

uint64_t pair_key(int32_t a, int32_t b) {
  return uint64_t(uint32_t(a)) << 32 | uint32_t(b);
}

// Calls visit(set index, element index, element nodes, computing parts) for every element of every set; the
// computing parts are the distinct owners of the element's nodes, in the order met. Checks each set's shape
// and node ids.
template <class Visit>
void for_each_element(std::span<const ElementNodes> sets, std::span<const int32_t> owner, Visit&& visit) {
  for (size_t s = 0; s < sets.size(); ++s) {
    const ElementNodes& set = sets[s];
    if (set.width < 1 || set.width > kMaxWidth || set.nodes.size() % size_t(set.width) != 0)
      throw Error(fmt::format("halo plan: {} has {} node ids for elements of {} nodes (at most {})", set.name,
                              set.nodes.size(), set.width, kMaxWidth));
    const size_t count = set.nodes.size() / size_t(set.width);
    for (size_t e = 0; e < count; ++e) {
      const std::span<const int32_t> nodes = set.nodes.subspan(e * size_t(set.width), size_t(set.width));
      std::array<int32_t, kMaxWidth> computing;
      int32_t k = 0;
      for (int32_t n : nodes) {
        if (n < 0 || size_t(n) >= owner.size())
          throw Error(
              fmt::format("halo plan: {} {} has node {}, not in [0, {})", set.name, e, n, owner.size()));
        const int32_t o = owner[size_t(n)];
        if (std::find(computing.begin(), computing.begin() + k, o) == computing.begin() + k)
          computing[size_t(k++)] = o;
      }
      visit(s, e, nodes, std::span<const int32_t>(computing.data(), size_t(k)));
    }
  }
}

void sort_unique(std::vector<int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

std::vector<int32_t> node_owners(int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                                 std::span<const ElementNodes> sets, std::span<const int32_t> node_units) {
  if (parts < 1 || sets.empty()) throw Error("halo plan: needs at least one part and the tets");
  const ElementNodes& tets = sets[0];
  if (tets.width < 1 || tets.nodes.size() != tet_part.size() * size_t(tets.width))
    throw Error(fmt::format("halo plan: {} parts given for {} of {} nodes each", tet_part.size(), tets.name,
                            tets.width));
  std::vector<int32_t> owner(size_t(nodes), -1);
  for (size_t e = 0; e < tet_part.size(); ++e) {
    if (tet_part[e] < 0 || tet_part[e] >= parts)
      throw Error(
          fmt::format("halo plan: {} {} is in part {}, not in [0, {})", tets.name, e, tet_part[e], parts));
    for (int32_t c = 0; c < tets.width; ++c) {
      const int32_t n = tets.nodes[e * size_t(tets.width) + size_t(c)];
      if (n < 0 || n >= nodes)
        throw Error(fmt::format("halo plan: {} {} has node {}, not in [0, {})", tets.name, e, n, nodes));
      if (owner[size_t(n)] < 0) owner[size_t(n)] = tet_part[e];
    }
  }
  const auto orphan = std::find(owner.begin(), owner.end(), -1);
  if (orphan != owner.end())
    throw Error(fmt::format("halo plan: node {} lies in none of the {}", orphan - owner.begin(), tets.name));
  own_by_unit(owner, node_units);
  return owner;
}

std::vector<int32_t> element_owners(const ElementNodes& set, std::span<const int32_t> node_owner) {
  if (set.width < 1 || set.nodes.size() % size_t(set.width) != 0)
    throw Error(
        fmt::format("halo plan: {} nodes for {} of {} nodes each", set.nodes.size(), set.name, set.width));
  std::vector<int32_t> owner(set.nodes.size() / size_t(set.width));
  for (size_t e = 0; e < owner.size(); ++e) {
    const int32_t first = set.nodes[e * size_t(set.width)];
    if (first < 0 || size_t(first) >= node_owner.size())
      throw Error(
          fmt::format("halo plan: {} {} has node {}, not in [0, {})", set.name, e, first, node_owner.size()));
    owner[e] = node_owner[size_t(first)];
  }
  return owner;
}

HaloPlan plan_halo(int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                   std::span<const ElementNodes> sets, std::span<const int32_t> node_units) {
  const std::vector<int32_t> owner = node_owners(parts, tet_part, nodes, sets, node_units);
  HaloPlan plan;
  plan.parts.resize(size_t(parts));
  for (const ElementNodes& s : sets) plan.element_sets.push_back(s.name);
  for (PartHalo& p : plan.parts) {
    p.computed.assign(sets.size(), 0);
    p.shared.assign(sets.size(), 0);
  }
  for (int32_t o : owner) ++plan.parts[size_t(o)].owned_nodes;

  // (part, ghost node) once per element that makes it a ghost; made unique below.
  std::vector<uint64_t> ghosts;
  for_each_element(sets, owner,
                   [&](size_t s, size_t, std::span<const int32_t> nodes, std::span<const int32_t> computing) {
                     for (int32_t part : computing) {
                       PartHalo& p = plan.parts[size_t(part)];
                       ++p.computed[s];
                       p.work += sets[s].weight;
                       if (computing.size() > 1) ++p.shared[s];
                       for (int32_t n : nodes)
                         if (owner[size_t(n)] != part) ghosts.push_back(pair_key(part, n));
                     }
                   });
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());

  // (receiving part, owning part) once per ghost node: the messages and their sizes.
  std::vector<uint64_t> links;
  links.reserve(ghosts.size());
  for (uint64_t g : ghosts) {
    const auto part = int32_t(g >> 32), node = int32_t(g & 0xffffffffu);
    ++plan.parts[size_t(part)].ghost_nodes;
    ++plan.parts[size_t(owner[size_t(node)])].nodes_sent;
    links.push_back(pair_key(part, owner[size_t(node)]));
  }
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  for (uint64_t l : links) {
    ++plan.parts[size_t(l >> 32)].receives_from;
    ++plan.parts[size_t(l & 0xffffffffu)].sends_to;
  }
  return plan;
}

RankHalo rank_halo(int32_t rank, int32_t parts, std::span<const int32_t> tet_part, int32_t nodes,
                   std::span<const ElementNodes> sets, std::span<const int32_t> node_units) {
  const std::vector<int32_t> owner = node_owners(parts, tet_part, nodes, sets, node_units);
  if (rank < 0 || rank >= parts) throw Error(fmt::format("halo plan: rank {} of {} parts", rank, parts));
  RankHalo h;
  h.rank = rank;
  for (size_t n = 0; n < owner.size(); ++n)
    if (owner[n] == rank) h.owned.push_back(int32_t(n));
  auto receive = std::vector<std::vector<int32_t>>(size_t(parts)), send = receive;
  h.elements.resize(sets.size());
  for_each_element(
      sets, owner,
      [&](size_t s, size_t e, std::span<const int32_t> nodes, std::span<const int32_t> computing) {
        if (std::find(computing.begin(), computing.end(), rank) == computing.end()) return;
        h.elements[s].push_back(int32_t(e));
        for (int32_t n : nodes) {
          const int32_t o = owner[size_t(n)];
          if (o != rank) {
            receive[size_t(o)].push_back(n);
            continue;
          }
          for (int32_t part : computing)
            if (part != rank) send[size_t(part)].push_back(n);
        }
      });
  for (int32_t q = 0; q < parts; ++q) {
    if (receive[size_t(q)].empty() && send[size_t(q)].empty()) continue;
    h.neighbours.push_back(q);
    sort_unique(receive[size_t(q)]);
    sort_unique(send[size_t(q)]);
    h.receive.push_back(std::move(receive[size_t(q)]));
    h.send.push_back(std::move(send[size_t(q)]));
  }
  return h;
}

}  // namespace rift
