#pragma once
// The one route by which forces reach the solid's nodes, and the order in which a node's sum takes them.
//
// Every producer of a force on the solid writes it into rows it owns; the node pass
// (systems/node_integration_system.cpp) gathers those rows per node, source by source in the order of
// kNodeForceRoute, and books each source's work in the energy column of its book (kBookWork). The order is
// fixed, so a node's total is the same bits on any number of threads.
//
// Rows reach a node in one of two ways:
//   slots      one row per element corner, at a place fixed at set-up; each node lists its slots
//              (solid_force_slot), grouped by source in the table's order;
//   node rows  one row per node (3 values), which the producer fills by gathering its own corner rows in
//              a fixed order (kernels/node_rows.hpp): for producers whose corners change between steps
//              (contact pairs, the fluid's coupling pairs) or which act on few of the nodes they could
//              (the faces of broken joints), where a slot per possible corner would gather mostly zeros.
#include <cstdint>
#include <iterator>

#include "systems/solid_tables.hpp"

namespace rift {

enum class NodeForceSource : uint8_t {
  tets,          // the tets' elastic and viscous forces
  joints,        // the joints' cohesive and residual friction forces (equal and opposite pairs)
  loaded_faces,  // surface loads: in-situ stress, pressure and traction on the solid's boundary
  fluid,         // the surrounding fluid's pressure and drag (systems/coupling)
  crack,         // pressure on the faces of broken joints: the scene's crack_pressure or the fracture flow
  contact,       // contact between the discrete surfaces of broken joints
};

enum class NodeForceRows : uint8_t { slots, node };

// Where a source's work goes. Internal forces (tets, joints, contact) are booked per source, since each
// is a term of the energy balance; external ones together, with gravity and the held components'
// reactions.
enum class NodeForceBook : uint8_t { tet = 0, joint = 1, external = 2, contact = 3 };

struct NodeForceRouteEntry {
  NodeForceSource source;
  const char* table;
  const char* column;
  NodeForceRows rows;
  NodeForceBook book;
};

// The solid_energy column of each book's work, by NodeForceBook.
inline constexpr const char* kBookWork[] = {"tet_work", "joint_work", "external_work", "contact_work"};
inline constexpr size_t kNodeForceBooks = std::size(kBookWork);
static_assert(static_cast<size_t>(NodeForceBook::contact) + 1 == kNodeForceBooks);

// The route, in gather order.
inline constexpr NodeForceRouteEntry kNodeForceRoute[] = {
    {NodeForceSource::tets, solid::tet_table, "corner_force", NodeForceRows::slots, NodeForceBook::tet},
    {NodeForceSource::joints, solid::joint_table, "corner_force", NodeForceRows::slots, NodeForceBook::joint},
    {NodeForceSource::loaded_faces, solid::face_table, "corner_force", NodeForceRows::slots,
     NodeForceBook::external},
    {NodeForceSource::fluid, solid::node_table, "fluid_force", NodeForceRows::node, NodeForceBook::external},
    {NodeForceSource::crack, solid::node_table, "crack_force", NodeForceRows::node, NodeForceBook::external},
    {NodeForceSource::contact, solid::node_table, "contact_force", NodeForceRows::node,
     NodeForceBook::contact},
};

constexpr const NodeForceRouteEntry& route_entry(NodeForceSource s) {
  return kNodeForceRoute[static_cast<size_t>(s)];
}

// The store column of a source (a producer of node rows writes it under this name).
constexpr const char* node_force_column(NodeForceSource s) {
  return route_entry(s).column;
}

namespace detail {
constexpr bool route_is_consistent() {
  for (size_t i = 0; i < std::size(kNodeForceRoute); ++i) {
    const NodeForceRouteEntry& e = kNodeForceRoute[i];
    if (static_cast<size_t>(e.source) != i) return false;  // route_entry indexes by source
    // The slot sources are kernels::ForceSlots's sources 0, 1, 2: tets, joints, loaded faces, whose work
    // the kernel books as work[0], [1], [2]; node rows come after them.
    if ((i < 3) != (e.rows == NodeForceRows::slots)) return false;
    if (i < 3 && static_cast<size_t>(e.book) != i) return false;
    // The kernel adds a node row to the external sum or to its fourth, internal one (work[3]).
    if (e.rows == NodeForceRows::node && e.book != NodeForceBook::external &&
        e.book != NodeForceBook::contact)
      return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::route_is_consistent());

}  // namespace rift
