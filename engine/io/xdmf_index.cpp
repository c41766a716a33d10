#include "engine/io/xdmf_index.hpp"

#include <charconv>
#include <cstdio>
#include <string_view>

#include "engine/core/error.hpp"
#include "engine/io/hdf5_file.hpp"

namespace rift::xdmf {
namespace {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Shortest text that reads back as the same double, so ParaView's time values equal the run's.
std::string format_time(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

const char* topology_name(Topology topology) {
  switch (topology) {
    case Topology::tetrahedron:
      return "Tetrahedron";
    case Topology::wedge:
      return "Wedge";
    case Topology::triangle:
      return "Triangle";
  }
  return "?";
}

const char* attribute_type(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 3:
      return "Vector";
    case 6:
      return "Tensor6";
    case 9:
      return "Tensor";
    default:
      return "Matrix";
  }
}

void data_item(std::string& out, const std::string& indent, const XdmfSeries::DataRef& ref) {
  out += indent + "<DataItem Dimensions=\"" + std::to_string(ref.rows);
  if (ref.components != 1) out += " " + std::to_string(ref.components);
  out += "\" NumberType=\"" + std::string(number_type(ref.type)) + "\" Precision=\"" +
         std::to_string(element_size(ref.type)) + "\" Format=\"HDF\">" + escape(ref.file) + ":" +
         escape(ref.path) + "</DataItem>\n";
}

void uniform_grid(std::string& out, const std::string& indent, const XdmfSeries::GridEntry& grid,
                  const std::string& time) {
  const std::string in1 = indent + "  ", in2 = indent + "    ";
  out += indent + "<Grid Name=\"" + escape(grid.name) + "\" GridType=\"Uniform\">\n";
  out += in1 + "<Time Value=\"" + time + "\"/>\n";
  out += in1 + "<Topology TopologyType=\"" + topology_name(grid.topology) + "\" NumberOfElements=\"" +
         std::to_string(grid.cells.rows) + "\">\n";
  data_item(out, in2, grid.cells);
  out += in1 + "</Topology>\n";
  out += in1 + "<Geometry GeometryType=\"XYZ\">\n";
  data_item(out, in2, grid.points);
  out += in1 + "</Geometry>\n";
  for (const auto& field : grid.fields) {
    out += in1 + "<Attribute Name=\"" + escape(field.name) + "\" AttributeType=\"" +
           attribute_type(field.data.components) + "\" Center=\"" +
           (field.center == Center::node ? "Node" : "Cell") + "\">\n";
    data_item(out, in2, field.data);
    out += in1 + "</Attribute>\n";
  }
  out += indent + "</Grid>\n";
}

}  // namespace

const char* number_type(ElementType type) {
  switch (type) {
    case ElementType::f64:
    case ElementType::f32:
      return "Float";
    case ElementType::i64:
    case ElementType::i32:
      return "Int";
    case ElementType::u32:
      return "UInt";
    case ElementType::u8:
      return "UChar";
  }
  return "?";
}

std::string render_index(const std::string& title, const std::vector<XdmfSeries::Entry>& entries) {
  std::string out = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  out += "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  out += "    <Grid Name=\"" + escape(title) + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& entry : entries) {
    const std::string time = format_time(entry.time);
    if (entry.grids.empty()) continue;  // nothing to show at this time
    // Always a spatial collection, also with one grid: the same structure at every time, so ParaView's
    // blocks keep their names (a step of one uniform grid between collections renamed them).
    char step[32];
    std::snprintf(step, sizeof step, "step_%08lld", static_cast<long long>(entry.step));
    out += std::string("      <Grid Name=\"") + step +
           "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    out += "        <Time Value=\"" + time + "\"/>\n";
    for (const auto& grid : entry.grids) uniform_grid(out, "        ", grid, time);
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out;
}

std::string render_grid_index(const std::string& grid, const std::vector<XdmfSeries::Entry>& entries) {
  std::string out = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  out += "    <Grid Name=\"" + escape(grid) + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& entry : entries)
    for (const auto& g : entry.grids)
      if (g.name == grid) uniform_grid(out, "      ", g, format_time(entry.time));
  out += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out;
}

namespace {

const char* topology_key(Topology t) {
  switch (t) {
    case Topology::tetrahedron:
      return "tetrahedron";
    case Topology::wedge:
      return "wedge";
    case Topology::triangle:
      return "triangle";
  }
  return "?";
}

nlohmann::json ref_to_json(const XdmfSeries::DataRef& ref) {
  return {{"file", ref.file},
          {"path", ref.path},
          {"rows", ref.rows},
          {"components", ref.components},
          {"type", element_type_name(ref.type)}};
}

XdmfSeries::DataRef ref_from_json(const nlohmann::json& j) {
  XdmfSeries::DataRef ref;
  ref.file = j.at("file").get<std::string>();
  ref.path = j.at("path").get<std::string>();
  ref.rows = j.at("rows").get<size_t>();
  ref.components = j.at("components").get<int>();
  const auto type = element_type_from_name(j.at("type").get<std::string>());
  if (!type) throw std::invalid_argument("unknown element type " + j.at("type").dump());
  ref.type = *type;
  return ref;
}

Topology topology_from(const std::string& key) {
  for (Topology t : {Topology::tetrahedron, Topology::wedge, Topology::triangle})
    if (key == topology_key(t)) return t;
  throw std::invalid_argument("unknown topology '" + key + "'");
}

}  // namespace

nlohmann::json entries_to_json(const std::vector<XdmfSeries::Entry>& entries) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& entry : entries) {
    nlohmann::json grids = nlohmann::json::array();
    for (const auto& g : entry.grids) {
      nlohmann::json fields = nlohmann::json::array();
      for (const auto& f : g.fields)
        fields.push_back({{"name", f.name},
                          {"center", f.center == Center::node ? "node" : "cell"},
                          {"data", ref_to_json(f.data)}});
      grids.push_back({{"name", g.name},
                       {"topology", topology_key(g.topology)},
                       {"mesh_revision", g.mesh_revision},
                       {"points", ref_to_json(g.points)},
                       {"cells", ref_to_json(g.cells)},
                       {"fields", fields}});
    }
    list.push_back({{"time", entry.time}, {"step", entry.step}, {"grids", grids}});
  }
  return {{"format", "rift-xdmf-series"}, {"version", 1}, {"entries", list}};
}

std::vector<XdmfSeries::Entry> entries_from_json(const nlohmann::json& json, const std::string& source) {
  std::vector<XdmfSeries::Entry> entries;
  try {
    if (json.at("format") != "rift-xdmf-series" || json.at("version") != 1)
      throw std::invalid_argument("expected format rift-xdmf-series version 1, found " +
                                  json.value("format", std::string("?")) + " version " +
                                  json.value("version", nlohmann::json()).dump());
    for (const auto& e : json.at("entries")) {
      XdmfSeries::Entry entry{e.at("time").get<double>(), e.at("step").get<int64_t>(), {}};
      for (const auto& g : e.at("grids")) {
        XdmfSeries::GridEntry grid{
            g.at("name").get<std::string>(),       topology_from(g.at("topology").get<std::string>()),
            g.at("mesh_revision").get<uint64_t>(), ref_from_json(g.at("points")),
            ref_from_json(g.at("cells")),          {}};
        for (const auto& f : g.at("fields")) {
          const std::string center = f.at("center").get<std::string>();
          if (center != "node" && center != "cell")
            throw std::invalid_argument("unknown center '" + center + "'");
          grid.fields.push_back({f.at("name").get<std::string>(),
                                 center == "node" ? Center::node : Center::cell,
                                 ref_from_json(f.at("data"))});
        }
        entry.grids.push_back(std::move(grid));
      }
      entries.push_back(std::move(entry));
    }
  } catch (const std::exception& e) {  // nlohmann::json::exception or the checks above
    throw Error("XDMF series index " + source + " is not readable: " + e.what());
  }
  return entries;
}

}  // namespace rift::xdmf
