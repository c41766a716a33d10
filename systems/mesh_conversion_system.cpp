#include "systems/mesh_conversion_system.hpp"

#include "systems/solid_tables.hpp"

namespace rift {

// The conversion's own state has no column in the store; its key orders consumers after it.
inline constexpr const char* conversion_key = "mesh_conversion.surface";

MeshConversionSystem::MeshConversionSystem(Store& store, MeshConversion& conversion)
    : store_(store), conversion_(conversion) {}

Access MeshConversionSystem::access() const {
  return {{solid::event::joint.key(), solid::event::time.key()}, {conversion_key}};
}

void MeshConversionSystem::catch_up() {
  const Table& events = store_.table(solid::event_table);
  const auto joint = solid::event::joint.read(events);
  const auto time = solid::event::time.read(events);
  for (; events_seen_ < events.size(); ++events_seen_)
    conversion_.break_joint(joint[events_seen_], time[events_seen_]);
}

}  // namespace rift
