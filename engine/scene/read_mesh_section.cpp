// mesh: a Gmsh file, or a box (with notches) or a disc the mesher generates, or lattice blocks.
#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"
#include "engine/io/input_file.hpp"
#include "engine/mesh/borehole_box.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "engine/scene/number_text.hpp"
#include "engine/scene/scene_names.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {
namespace {

constexpr std::array<std::string_view, 6> kFaces{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

std::string interval_text(double lo, double hi) {
  return "(" + message_real(lo) + ", " + message_real(hi) + ")";
}

// Checks that a notch lies in the box; only values that were read correctly are compared, so one
// typo gives one message.
void check_notch_fits(MapReader& n, const NotchSpec& notch, const MeshGenerateSpec& box, int face_axis) {
  const int a = notch.opening_axis;
  const std::string axis(kAxes[a]);
  if (n.ok("depth") && n.ok("face") && notch.depth >= box.size[face_axis])
    n.error("depth", "a depth in m, in " + interval_text(0, box.size[face_axis]) + " (the box size along " +
                         std::string(kAxes[face_axis]) + ")");
  if (n.ok("opening_axis") && n.ok("face") && a == face_axis) {
    n.error("opening_axis", "an axis other than " + axis + ", the normal of face " + notch.face);
    return;
  }
  if (!n.ok("opening_axis")) return;
  const double lo = box.origin[a], hi = box.origin[a] + box.size[a];
  if (n.ok("center") && !(notch.center > lo && notch.center < hi))
    n.error("center", "a coordinate in m inside the box along " + axis + ", in " + interval_text(lo, hi));
  if (n.ok("center") && n.ok("opening") &&
      !(notch.center - 0.5 * notch.opening > lo && notch.center + 0.5 * notch.opening < hi)) {
    const double room = 2.0 * std::min(notch.center - lo, hi - notch.center);
    n.error("opening", "an opening in m < " + message_real(room) +
                           " so the notch stays inside the box along " + axis + " " + interval_text(lo, hi));
  }
}

NotchSpec read_notch(MapReader& n, const MeshGenerateSpec& box, bool box_ok) {
  NotchSpec notch;
  notch.shape = n.choice("shape", scene_names::kNotchShape, std::optional<NotchSpec::Shape>());
  const size_t face = n.choice("face", kFaces, std::nullopt);
  notch.face = std::string(kFaces[face]);
  notch.opening_axis = static_cast<int>(n.choice("opening_axis", kAxes, std::nullopt));
  notch.center = n.real("center", any_real("m"), std::nullopt);
  notch.depth = n.real("depth", positive("m"), std::nullopt);
  notch.opening = n.real("opening", positive("m"), std::nullopt);
  notch.name = n.string("name", std::string("notch"));
  if (box_ok) check_notch_fits(n, notch, box, static_cast<int>(face / 2));
  n.finish();
  return notch;
}

CylinderSpec read_cylinder(MapReader& c) {
  CylinderSpec cylinder;
  cylinder.diameter = c.real("diameter", positive("m"), std::nullopt);
  cylinder.thickness = c.real("thickness", positive("m"), std::nullopt);
  cylinder.load_arc = c.real("load_arc", RealRule{"deg", 0.0, 90.0, true, true}, 10.0);
  c.finish();
  return cylinder;
}

BlockSpec read_block(MapReader& b, size_t index) {
  BlockSpec block;
  block.name = b.string("name", "block" + std::to_string(index));
  b.default_varies("name");
  block.origin = b.vec3("origin", any_real("m"), std::array<double, 3>{});
  block.size = b.vec3("size", positive("m"), std::nullopt);
  // Exactly one of cells (a lattice) and element_size (an unstructured mesh); the other is read through
  // b.unused(), so that it is known with its rule.
  const auto read_size = [](auto&& r) { return r.real("element_size", positive("m"), std::nullopt); };
  const auto read_cells = [](auto&& r) {
    return r.vec3("cells", RealRule{"", 1.0, 4096.0, false, false}, std::nullopt);
  };
  const bool has_size = b.has("element_size"), has_cells = b.has("cells");
  if (has_size && !has_cells) {
    block.element_size = read_size(b);
    read_cells(b.unused());
  } else {
    const std::array<double, 3> cells = read_cells(b);
    for (int a = 0; a < 3; ++a) block.cells[a] = static_cast<int>(cells[a]);
    if (b.ok("cells") &&
        (cells[0] != block.cells[0] || cells[1] != block.cells[1] || cells[2] != block.cells[2]))
      b.error("cells", "three whole numbers of cubes, each in [1, 4096]");
    if (has_size) b.error("element_size", "either cells or element_size, not both");
    read_size(b.unused());
  }
  b.finish();
  return block;
}

// Exactly one of box / cylinder / blocks. Keys of the shapes not used are read through g.unused(), which
// reports nothing, so the docs test and the schema know them whichever shape a scene uses.
void read_shape(MapReader& g, MeshGenerateSpec& spec) {
  const bool has_box = g.has("box"), has_cylinder = g.has("cylinder"), has_blocks = g.has("blocks");
  const int shapes = int(has_box) + int(has_cylinder) + int(has_blocks);
  if (shapes != 1 && !g.silent())
    g.context().error(
        shapes == 0 ? g.where() : g.where(has_box ? (has_cylinder ? "cylinder" : "blocks") : "blocks"),
        g.path(),
        "exactly one of " + g.key_path("box") + ", " + g.key_path("cylinder") + " or " + g.key_path("blocks"),
        shapes == 0 ? "none" : "more than one");
  const auto box = [](auto&& r) { return r.vec3("box", positive("m"), std::nullopt); };
  if (has_box && shapes == 1)
    spec.size = box(g);
  else
    box(g.unused());
  if (has_cylinder && shapes == 1) {
    spec.shape = MeshGenerateSpec::Shape::cylinder;
    MapReader c = g.section("cylinder", false);
    spec.cylinder = read_cylinder(c);
  } else {
    MapReader unused = g.unused().section("cylinder", false);
    read_cylinder(unused);
  }
  if (has_blocks && shapes == 1) {
    spec.shape = MeshGenerateSpec::Shape::blocks;
    auto blocks = g.section_list("blocks", 1);
    for (size_t k = 0; k < blocks.size(); ++k) spec.blocks.push_back(read_block(blocks[k], k));
  } else {
    for (MapReader& unused : g.unused().section_list("blocks", 1)) read_block(unused, 0);
  }
}

// Reports the fine box's first problem along axis `a`; true when there was one.
bool fine_axis_error(MapReader& r, const LatticeGradingSpec& g, const MeshGenerateSpec& box, bool box_ok,
                     int a) {
  const double lo = box.origin[a], hi = box.origin[a] + box.size[a];
  const std::string axis(kAxes[a]);
  if (!(g.fine_max[a] > g.fine_min[a])) {
    r.error("fine_max",
            "each coordinate above fine_min's (" + message_real(g.fine_min[a]) + " along " + axis + ")");
    return true;
  }
  if (box_ok && !(g.fine_max[a] > lo && g.fine_min[a] < hi)) {
    r.error("fine_max", "a fine box that overlaps the box along " + axis + " " + interval_text(lo, hi));
    return true;
  }
  if (r.ok("size") && (std::min(hi, g.fine_max[a]) - std::max(lo, g.fine_min[a])) / g.size > 1e6) {
    r.error("size", "at most 1e6 cells across the fine box along " + axis);
    return true;
  }
  return false;
}

// graded: the fine box must overlap the box along every axis (checked when both were read); one message
// at most, for the first axis that fails.
LatticeGradingSpec read_grading(MapReader& r, const MeshGenerateSpec& box, bool box_ok) {
  LatticeGradingSpec spec;
  spec.fine_min = r.vec3("fine_min", any_real("m"), std::nullopt);
  spec.fine_max = r.vec3("fine_max", any_real("m"), std::nullopt);
  spec.size = r.real("size", positive("m"), std::nullopt);
  spec.growth = r.real("growth", RealRule{"", 1.0, 2.0, false, false}, 1.25);
  if (r.ok("fine_min") && r.ok("fine_max"))
    for (int a = 0; a < 3 && !fine_axis_error(r, spec, box, box_ok, a); ++a) {
    }
  r.finish();
  return spec;
}

// borehole: the hole must fit the box (checked by the generator's own count, which names the problem).
BoreholeMeshSpec read_borehole(MapReader& r, const MeshGenerateSpec& box, bool box_ok) {
  BoreholeMeshSpec spec;
  spec.axis_x = r.real("axis_x", any_real("m"), std::nullopt);
  spec.axis_y = r.real("axis_y", any_real("m"), std::nullopt);
  spec.radius = r.real("radius", positive("m"), std::nullopt);
  spec.size = r.real("size", positive("m"), std::nullopt);
  if (r.ok("radius") && r.ok("size") && spec.size > spec.radius)
    r.error("size", "a cell size at the wall of at most the radius (" + message_real(spec.radius) + " m)");
  // Default: square cells at the wall, each ring as much thicker as its circumference is longer.
  const double square =
      r.ok("radius") && r.ok("size") ? std::min(2.0, std::exp(spec.size / spec.radius)) : 1.0;
  spec.growth = r.real("growth", RealRule{"", 1.0, 2.0, false, false}, square);
  r.default_varies("growth");
  if (box_ok && r.ok("axis_x") && r.ok("axis_y") && r.ok("radius") && r.ok("size") && r.ok("growth") &&
      spec.size <= spec.radius) {
    try {
      borehole_box_counts(borehole_box_spec(box.origin, box.size, spec));
    } catch (const Error& e) {
      r.error("radius", std::string("a borehole that fits the box: ") + e.what());
    }
  }
  r.finish();
  return spec;
}

// cells: [nx, ny, nz], whole numbers >= 1.
std::optional<std::array<int, 3>> read_cells(MapReader& g) {
  const std::array<double, 3> c = g.vec3("cells", RealRule{"", 1.0, 1e6, false, false}, std::nullopt);
  if (!g.ok("cells")) return std::nullopt;
  std::array<int, 3> cells{};
  for (int d = 0; d < 3; ++d) {
    if (c[d] != std::floor(c[d])) {
      g.error("cells", "three whole numbers of cells >= 1 (nx, ny, nz)");
      return std::nullopt;
    }
    cells[d] = static_cast<int>(c[d]);
  }
  return cells;
}

// A section this shape could have but the scene does not give: its key and its keys are known (read
// through g.unused(), which reports nothing), so that they count as declared and have their rules.
template <class Read>
void declare_section(MapReader& g, const char* key, const Read& read) {
  MapReader unused = g.unused().section(key, false);
  read(unused);
}

MeshGenerateSpec read_generate(MapReader& g) {
  MeshGenerateSpec spec;
  read_shape(g, spec);
  if (spec.shape == MeshGenerateSpec::Shape::blocks) {
    // A lattice: its element size is the cells', so the mesher's size keys do not apply.
    for (auto key : {"origin", "cells", "size_min", "size_max", "grading", "seed"})
      g.forbid(key, "for blocks (each block gives its origin, size and cells)");
    g.forbid("notches", "for blocks (notches cut a generated box)");
    g.finish();
    return spec;
  }
  spec.origin = g.vec3("origin", any_real("m"), std::array<double, 3>{});
  if (g.has("borehole") && spec.shape == MeshGenerateSpec::Shape::box) {  // a box with a hole
    MapReader r = g.section("borehole", false);
    spec.borehole = read_borehole(r, spec, g.has("box") && g.ok("box") && g.ok("origin"));
    for (auto key : {"cells", "size_min", "size_max", "grading", "seed", "notches", "graded"})
      g.forbid(key, "with borehole (the hole's lattice has its own sizes; no seed or notches)");
    g.finish();
    return spec;
  }
  if (spec.shape == MeshGenerateSpec::Shape::cylinder)
    g.forbid("borehole", "for a cylinder (a borehole is cut in a box)");
  else
    declare_section(g, "borehole", [&](MapReader& r) { read_borehole(r, spec, false); });
  if (g.has("graded") && spec.shape == MeshGenerateSpec::Shape::box) {  // a graded lattice
    MapReader r = g.section("graded", false);
    spec.graded = read_grading(r, spec, g.has("box") && g.ok("box") && g.ok("origin"));
    for (auto key : {"cells", "size_min", "size_max", "grading", "seed", "notches"})
      g.forbid(key, "with graded (a graded lattice's sizes are its own; no seed or notches)");
    g.finish();
    return spec;
  }
  if (spec.shape == MeshGenerateSpec::Shape::cylinder)
    g.forbid("graded", "for a cylinder (a lattice is a box)");
  else
    declare_section(g, "graded", [&](MapReader& r) { read_grading(r, spec, false); });
  if (g.has("cells") && spec.shape == MeshGenerateSpec::Shape::box) {  // a lattice: no sizing, no notches
    spec.cells = read_cells(g);
    for (auto key : {"size_min", "size_max", "grading", "seed", "notches"})
      g.forbid(key, "with cells (a structured lattice has no sizing, seed or notches)");
    g.finish();
    return spec;
  }
  if (spec.shape == MeshGenerateSpec::Shape::cylinder) {
    g.forbid("cells", "for a cylinder (a structured lattice is a box)");
  } else {
    MapReader unused = g.unused();
    read_cells(unused);
  }
  spec.size_min = g.real("size_min", positive("m"), std::nullopt);
  spec.size_max = g.real("size_max", positive("m"), std::nullopt);
  if (g.ok("size_min") && g.ok("size_max") && spec.size_max < spec.size_min)
    g.error("size_max", "a number in m, >= size_min (" + message_real(spec.size_min) + ")");
  spec.grading = g.real("grading", positive(""), 0.5);
  spec.seed = static_cast<uint32_t>(g.integer("seed", IntRule{0, UINT32_MAX}, 1));
  if (spec.shape == MeshGenerateSpec::Shape::cylinder) {
    g.forbid("notches", "for a cylinder (notches cut boxes)");
  } else {
    // Fits are checked only against a box that was read (not with both shapes or neither given).
    const bool box_ok = g.has("box") && !g.has("cylinder") && g.ok("box") && g.ok("origin");
    for (auto& n : g.section_list("notches", 0)) spec.notches.push_back(read_notch(n, spec, box_ok));
  }
  g.finish();
  return spec;
}

// The file must exist now: a wrong path found at t = 0 beats one found after meshing starts.
std::string resolve_mesh_file(MapReader& sec, const std::string& file, const std::string& base_dir) {
  namespace fs = std::filesystem;
  fs::path path = fs::path(base_dir) / file;
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (!ec) path = absolute;
  path = path.lexically_normal();
  if (!fs::is_regular_file(path, ec))
    sec.error("file", "the path of an existing Gmsh MSH file (relative paths start at the scene's folder)",
              "no file at " + path.string());
  return path.string();
}

}  // namespace

MeshSpec read_mesh_section(MapReader& sec, const std::string& base_dir) {
  MeshSpec mesh;
  const bool has_file = sec.has("file"), has_generate = sec.has("generate");
  if (has_file == has_generate && !sec.silent()) {
    const std::string expected = "exactly one of " + sec.key_path("file") + " or " + sec.key_path("generate");
    if (has_file)
      sec.context().error(sec.where("generate"), sec.path(), expected, "both");
    else
      sec.context().error(sec.where(), sec.path(), expected, "neither");
  }
  mesh.max_file_bytes = static_cast<uint64_t>(
      sec.integer("max_file_bytes", IntRule{1, INT64_MAX}, static_cast<int64_t>(msh_default_max_bytes)));
  if (has_file) {
    std::string file = sec.string("file", std::nullopt);
    if (sec.ok("file")) {
      mesh.file = resolve_mesh_file(sec, file, base_dir);
      sec.resolved_value("file", resolved_string(*mesh.file));  // absolute: reads back from anywhere
    }
    // The content is part of the scene's hash: a restart refuses a mesh file replaced at the same path.
    if (sec.ok("file") && sec.ok("max_file_bytes")) {
      try {
        const InputFileLimit limit{mesh.max_file_bytes, sec.key_path("max_file_bytes")};
        mesh.file_fnv1a64 = hex16(hash_input_file(*mesh.file, limit, "mesh file"));
      } catch (const Error& e) {
        sec.error("file", "a readable Gmsh MSH file of at most " + sec.key_path("max_file_bytes") + " bytes",
                  e.what());
      }
    }
  } else {
    sec.unused().string("file", std::nullopt);
  }
  mesh.scale = sec.real("scale", positive(""), 1.0);
  const auto max_elements = static_cast<uint64_t>(
      sec.integer("max_elements", IntRule{1, INT64_MAX}, static_cast<int64_t>(kDefaultMaxElements)));
  MapReader generate = sec.section("generate", false);
  if (has_generate) {
    mesh.generate = read_generate(generate);
    mesh.generate->max_elements = max_elements;
    mesh.generate->max_elements_key = sec.key_path("max_elements");
  }
  sec.finish();
  return mesh;
}

}  // namespace rift
