#pragma once
// Internal to the joint kernels (scalar and AVX2 paths): flag a joint as broken and append its event.
#include "kernels/joint_forces.hpp"

namespace rift::kernels::joint_detail {

inline void record_break(const JointArgs& a, size_t j, JointBreakMode mode, double stored_energy,
                         JointStatus& status) {
  a.broken[j] = static_cast<uint8_t>(mode);
  ++status.broke;
  const size_t slot = a.breaks.empty() ? 0 : a.break_count->fetch_add(1, std::memory_order_relaxed);
  if (slot < a.breaks.size())
    a.breaks[slot] = {static_cast<int32_t>(j), mode, stored_energy};
  else
    ++status.breaks_dropped;
}

}  // namespace rift::kernels::joint_detail
