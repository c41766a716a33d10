#pragma once
// The console's end of a run: what the physics did, read from the summary.json the run wrote (so the
// console says exactly what the file says), and the whole wall time, meshing included.
#include <nlohmann/json.hpp>
#include <string>

namespace rift {

// Lines "physics: ..." for the models present in summary["metrics"] (breaks by mode, energy balance,
// fragments, fracture flow, fluid solves) and "wall time: ..."; empty sections are left out.
std::string run_report(const nlohmann::json& summary);

}  // namespace rift
