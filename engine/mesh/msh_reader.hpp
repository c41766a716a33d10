#pragma once
// Gmsh MSH in (4.1 and 2.2, ASCII and binary) and out (4.1 ASCII), with our own parser (libgmsh would pull
// OpenCASCADE and FLTK into the core for a few hundred lines of format). What is read:
//   $MeshFormat: version 4.1 or 2.2, file type 0 (ASCII) or 1 (binary). A binary file must have data size
//     8 (size_t in 4.1, double in 2.2) and be little-endian (the int 1 after the format line reads 1);
//     MSH 1, 3 and 4.0, a big-endian file and a partitioned 4.1 mesh ($PartitionedEntities) are refused
//     with a hint to convert the file with gmsh.
//   $PhysicalNames; 4.1: $Entities, $Nodes and $Elements in entity blocks; 2.2: $Nodes and $Elements, an
//     element's first tag its physical group, its second its elementary entity (physical tag 0: none).
//   Element type 4 (4-node tet) and 2 (3-node triangle) are kept; every other type is skipped and
//   counted (in a binary file a type must be one whose node count is known, msh_element_types.hpp, or
//   its records cannot be skipped: an error naming it). Unknown sections ($Periodic, $NodeData,
//   $Comments, ...) are skipped.
// How groups become names:
//   physical volume  -> region  (name from $PhysicalNames, else "volume_<tag>"); a tet in no physical
//                       volume goes to region "domain"; an entity in several physical volumes gives
//                       its tets the first one listed (2.2, where Gmsh writes such a tet once per group
//                       in a row, keeps the first record).
//   physical surface -> surface (name from $PhysicalNames, else "surface_<tag>"); a triangle whose
//                       entity is in several physical surfaces is listed once per surface (2.2: once
//                       per record); a triangle in none is dropped (counted).
//   Regions and surfaces are ordered by physical tag; "domain", when needed, comes last.
// Node tags may be sparse; nodes are renumbered densely in file order, and nodes that no tet uses are
// dropped (a solid node without mass would break the physics).
// Tets with negative orientation are flipped (nodes 1 and 2 swapped); a degenerate tet, a tet listed twice
// and two nodes of tets at one point are errors.
// The file is refused before it is read when it is no regular file or larger than the limit (the scene
// key mesh.max_file_bytes, 2 GiB by default), and read as a stream through a window of 1 MiB: memory
// holds the mesh being built, never the file; a token longer than the window is an error, binary data
// is read across the window's boundaries, and no count read from the file sizes an allocation beyond
// what the file's size can hold. A file that does not start with $MeshFormat is refused without quoting
// any of it, and other errors quote at most the offending token or value.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/input_file.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// 2 GiB of MSH text is some 20 million tets (of binary MSH 4.1, some 50 million); reading it takes
// several times that in memory.
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

// Reads a Gmsh MSH 4.1 or 2.2 file, ASCII or binary; coordinates are multiplied by `scale` (1e-3 for a
// mesh in mm). Throws rift::Error "path:line: expected ..., found ..." on anything malformed, and
// "path: byte offset N: expected ..., found ..." for binary data. `window_bytes` is the streaming window
// (tests read through tiny windows to cross every boundary).
TetMesh read_msh(const std::string& path, double scale = 1.0, MshReadStats* stats = nullptr,
                 const InputFileLimit& limit = {msh_default_max_bytes, "mesh.max_file_bytes"},
                 size_t window_bytes = msh_window_bytes);

// Writes `mesh` as MSH 4.1 ASCII: one physical volume per region, one physical surface per surface
// name (tags 1, 2, ... in name order), coordinates in shortest round-trip form, so that read_msh gives
// back the same mesh (nodes no tet uses excepted). Throws rift::Error if the file cannot be written.
void write_msh(const TetMesh& mesh, const std::string& path);

}  // namespace rift
