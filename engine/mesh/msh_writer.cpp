// Gmsh MSH 4.1 ASCII writer (declared in msh_reader.hpp). One geometric entity per surface name and per
// region, each in its own physical group with the same tag; all nodes in one block on the first volume.
// Elements are written in runs of consecutive equal group, so the element order survives a round trip.
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "engine/core/error.hpp"
#include "engine/mesh/msh_reader.hpp"

namespace rift {
namespace {

using Out = std::back_insert_iterator<std::string>;

void check_name(const std::string& name, const std::string& path) {
  if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos)
    throw Error(path + ": expected group names without double quotes or line breaks, found '" + name + "'");
}

// Number of maximal runs of equal values: one element block each.
size_t run_count(const std::vector<int32_t>& groups) {
  size_t runs = 0;
  for (size_t i = 0; i < groups.size(); ++i) runs += (i == 0 || groups[i] != groups[i - 1]);
  return runs;
}

// Writes the elements of `cells` in blocks of consecutive equal `groups`; entity tag = group + 1.
template <size_t N>
void write_blocks(Out out, int dim, int type, const std::vector<std::array<int32_t, N>>& cells,
                  const std::vector<int32_t>& groups, size_t& next_tag) {
  size_t i = 0;
  while (i < cells.size()) {
    size_t end = i;
    while (end < cells.size() && groups[end] == groups[i]) ++end;
    fmt::format_to(out, "{} {} {} {}\n", dim, groups[i] + 1, type, end - i);
    for (; i < end; ++i) {
      fmt::format_to(out, "{}", next_tag++);
      for (const int32_t v : cells[i]) fmt::format_to(out, " {}", v + 1);
      *out++ = '\n';
    }
  }
}

void write_header_and_groups(Out out, const TetMesh& mesh, const std::string& path) {
  fmt::format_to(out, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  const size_t surfaces = mesh.surface_names.size(), regions = mesh.region_names.size();
  fmt::format_to(out, "$PhysicalNames\n{}\n", surfaces + regions);
  for (size_t s = 0; s < surfaces; ++s) {
    check_name(mesh.surface_names[s], path);
    fmt::format_to(out, "2 {} \"{}\"\n", s + 1, mesh.surface_names[s]);
  }
  for (size_t r = 0; r < regions; ++r) {
    check_name(mesh.region_names[r], path);
    fmt::format_to(out, "3 {} \"{}\"\n", r + 1, mesh.region_names[r]);
  }
  fmt::format_to(out, "$EndPhysicalNames\n");
  // Every entity gets the bounding box of the whole mesh: readers use it for display only.
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  if (!mesh.nodes.empty()) lo = hi = mesh.nodes.front();
  for (const auto& x : mesh.nodes)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  const std::string box = fmt::format("{} {} {} {} {} {}", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  fmt::format_to(out, "$Entities\n0 0 {} {}\n", surfaces, regions);
  for (size_t s = 0; s < surfaces; ++s) fmt::format_to(out, "{} {} 1 {} 0\n", s + 1, box, s + 1);
  for (size_t r = 0; r < regions; ++r) fmt::format_to(out, "{} {} 1 {} 0\n", r + 1, box, r + 1);
  fmt::format_to(out, "$EndEntities\n");
}

void write_nodes(Out out, const TetMesh& mesh) {
  const size_t n = mesh.nodes.size();
  fmt::format_to(out, "$Nodes\n{} {} {} {}\n", n ? 1 : 0, n, n ? 1 : 0, n);
  if (n) {
    fmt::format_to(out, "3 1 0 {}\n", n);
    for (size_t i = 0; i < n; ++i) fmt::format_to(out, "{}\n", i + 1);
    // fmt prints the shortest decimal that reads back to the same double: the round trip is exact.
    for (const auto& x : mesh.nodes) fmt::format_to(out, "{} {} {}\n", x[0], x[1], x[2]);
  }
  fmt::format_to(out, "$EndNodes\n");
}

}  // namespace

void write_msh(const TetMesh& mesh, const std::string& path) {
  if (mesh.tet_region.size() != mesh.tets.size() || mesh.triangle_surface.size() != mesh.triangles.size())
    throw Error(path + ": expected one region per tet and one surface per triangle in the mesh to write");
  if (!mesh.nodes.empty() && mesh.region_names.empty())
    throw Error(path + ": expected at least one region name in the mesh to write");
  std::string text;
  text.reserve(64 * (mesh.nodes.size() + mesh.tets.size() + mesh.triangles.size()) + 4096);
  Out out(text);
  write_header_and_groups(out, mesh, path);
  write_nodes(out, mesh);
  const size_t blocks = run_count(mesh.triangle_surface) + run_count(mesh.tet_region);
  const size_t elements = mesh.triangles.size() + mesh.tets.size();
  fmt::format_to(out, "$Elements\n{} {} {} {}\n", blocks, elements, elements ? 1 : 0, elements);
  size_t next_tag = 1;
  write_blocks(out, 2, 2, mesh.triangles, mesh.triangle_surface, next_tag);
  write_blocks(out, 3, 4, mesh.tets, mesh.tet_region, next_tag);
  fmt::format_to(out, "$EndElements\n");

  std::ofstream file(path, std::ios::binary);
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!file) throw Error(path + ": cannot write the mesh file (is the folder there and writable?)");
}

}  // namespace rift
