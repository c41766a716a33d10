#pragma once
// Gmsh MSH 4.1 ASCII in and out, with our own parser (libgmsh would pull OpenCASCADE and FLTK into the
// core for a few hundred lines of format). What is read:
//   $MeshFormat (4.1, ASCII only), $PhysicalNames, $Entities, $Nodes and $Elements in entity blocks.
//   Element type 4 (4-node tet) and 2 (3-node triangle) are kept; every other type is skipped and
//   counted. Unknown sections ($Periodic, $NodeData, $Comments, ...) are skipped.
// How groups become names:
//   physical volume  -> region  (name from $PhysicalNames, else "volume_<tag>"); a tet in no physical
//                       volume goes to region "domain"; an entity in several physical volumes gives
//                       its tets the first one listed.
//   physical surface -> surface (name from $PhysicalNames, else "surface_<tag>"); a triangle whose
//                       entity is in several physical surfaces is listed once per surface; a triangle
//                       in none is dropped (counted).
//   Regions and surfaces are ordered by physical tag; "domain", when needed, comes last.
// Node tags may be sparse; nodes are renumbered densely in file order, and nodes that no tet uses are
// dropped (a solid node without mass would break the physics).
// Tets with negative orientation are flipped (nodes 1 and 2 swapped); a degenerate tet is an error.
// The file is refused before it is read when it is no regular file or larger than the limit (the scene
// key mesh.max_file_bytes, 2 GiB by default), and read as a stream through a window of 1 MiB: memory
// holds the mesh being built, never the file's text; a token longer than the window is an error. A file that
// does not start with $MeshFormat is refused without quoting any of it, and other errors quote at most the
// offending token.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/input_file.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// 2 GiB of MSH text is some 20 million tets; reading it takes several times that in memory.
inline constexpr uint64_t msh_default_max_bytes = uint64_t{2} << 30;
// The longest token or quoted name read_msh accepts; lines it skips may be longer.
inline constexpr size_t msh_window_bytes = size_t{1} << 20;

// What read_msh did besides building the mesh, for the log.
struct MshReadStats {
  size_t nodes_in_file = 0;
  size_t unused_nodes_dropped = 0;  // nodes referenced by no tet
  size_t tets = 0;
  size_t flipped_tets = 0;                               // negative orientation in the file, fixed
  size_t triangles_without_surface = 0;                  // triangles in no physical surface, dropped
  std::vector<std::pair<int, size_t>> skipped_elements;  // Gmsh element type -> count, by type
  uint64_t content_fnv1a64 = 0;                          // FNV-1a 64 of the bytes that were parsed
};

// Reads a Gmsh MSH 4.1 ASCII file; coordinates are multiplied by `scale` (1e-3 for a mesh in mm).
// Throws rift::Error "path:line: expected ..., found ..." on anything malformed. `window_bytes` is the
// streaming window (tests read through tiny windows to cross every boundary).
TetMesh read_msh(const std::string& path, double scale = 1.0, MshReadStats* stats = nullptr,
                 const InputFileLimit& limit = {msh_default_max_bytes, "mesh.max_file_bytes"},
                 size_t window_bytes = msh_window_bytes);

// Writes `mesh` as MSH 4.1 ASCII: one physical volume per region, one physical surface per surface
// name (tags 1, 2, ... in name order), coordinates in shortest round-trip form, so that read_msh gives
// back the same mesh (nodes no tet uses excepted). Throws rift::Error if the file cannot be written.
void write_msh(const TetMesh& mesh, const std::string& path);

}  // namespace rift
