#pragma once
// Text forms of an XdmfSeries' entries: the XDMF 2.0 index ParaView reads and the JSON sidecar a
// restart reloads. Pure functions of the entries, so the index can always be regenerated whole.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/io/xdmf_series.hpp"

namespace rift::xdmf {

// The complete .xdmf document; `title` names the temporal collection.
std::string render_index(const std::string& title, const std::vector<XdmfSeries::Entry>& entries);

// The index of one grid alone (XDMF 3.0): a temporal collection of that grid's uniform grids, one per
// entry that has it. One dataset, one stable block name, nothing drawn over it; the layout meshio's
// TimeSeriesReader reads (it wants version 3 and uniform grids directly under the temporal collection).
std::string render_grid_index(const std::string& grid, const std::vector<XdmfSeries::Entry>& entries);

nlohmann::json entries_to_json(const std::vector<XdmfSeries::Entry>& entries);
// Throws rift::Error naming `source` (the sidecar's path) when the JSON does not describe entries.
std::vector<XdmfSeries::Entry> entries_from_json(const nlohmann::json& json, const std::string& source);

// "Float"/"Int"/"UInt"/"UChar" and the byte size, as XDMF's NumberType and Precision attributes.
const char* number_type(ElementType type);

}  // namespace rift::xdmf
