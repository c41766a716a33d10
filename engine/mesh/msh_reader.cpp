// Gmsh MSH reader. Layout reference: the "MSH file format" chapter of the Gmsh manual (4.1, and 2.2 under
// the legacy formats). The $MeshFormat line gives the version and the file type; the sections that differ
// between versions are read by msh41_sections.cpp and msh22_sections.cpp, through MshFields (ASCII tokens or
// binary values), into the mesh being built (msh_mesh_builder.hpp). One pass over the file, streamed through
// a window (memory holds the mesh, not the file); every record is parsed once, node tags are mapped through
// a dense array (or a hash map when tags are very sparse) and physical tags through hash maps, so the cost
// is O(file size) however many physical groups the file has.
#include "engine/mesh/msh_reader.hpp"

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/mesh/msh_sections.hpp"
#include "engine/mesh/text_cursor.hpp"

namespace rift {
namespace {

const char* kConvertHint =
    "; convert it with `gmsh in.msh -save -format msh41 -o out.msh` "
    "(or in the Gmsh GUI: File > Export, format Gmsh MSH, Version 4 ASCII)";

struct MshFormat {
  int version = 0;  // 41 or 22
  bool binary = false;
  bool operator==(const MshFormat&) const = default;
};

// version file-type data-size, and in a binary file the int 1 on the next line: a little-endian file reads
// it as 1 (the reader decodes little-endian, whatever the machine).
MshFormat read_format(TextCursor& cur, uint64_t file_size) {
  MshFormat format;
  const std::string_view version = cur.token();
  format.version = version == "4.1" ? 41 : version == "2.2" ? 22 : 0;
  if (format.version == 0)
    cur.fail("MSH format version 4.1 or 2.2", TextCursor::describe(version) + kConvertHint);
  const int64_t file_type = cur.integer("file type");
  if (file_type != 0 && file_type != 1)
    cur.fail("file type 0 (ASCII) or 1 (binary)", std::to_string(file_type));
  format.binary = file_type == 1;
  const int64_t data_size = cur.integer("data size");
  if (format.binary) {  // an ASCII file's data size means nothing
    if (data_size != 8)
      cur.fail(format.version == 41 ? "data size 8 (the size of a size_t in a binary MSH 4.1 file)"
                                    : "data size 8 (the size of a double in a binary MSH 2.2 file)",
               std::to_string(data_size) + kConvertHint);
    MshFields binary(cur, true, file_size);
    binary.begin_data();
    const int one = binary.int32("the binary integer 1 (the endianness check)");
    if (one == (1 << 24))
      binary.fail("a little-endian file (the binary integer 1 reads 1)",
                  "a big-endian file (it reads 16777216)" + std::string(kConvertHint));
    if (one != 1) binary.fail("the binary integer 1 (the endianness check)", std::to_string(one));
  }
  const std::string_view end = cur.token();
  if (end != "$EndMeshFormat") cur.fail("$EndMeshFormat", TextCursor::describe(end));
  return format;
}

}  // namespace

// numNames, then per name: dimension tag "name".
void read_msh_physical_names(MshFields& f, MshMeshBuilder& mesh) {
  TextCursor& cur = f.cursor();
  const int64_t n = f.count(f.text_integer("number of physical names"), "number of physical names", 2);
  for (int64_t i = 0; i < n; ++i) {
    const int64_t dim = cur.integer("physical group dimension");
    if (dim < 0 || dim > 3) cur.fail("a dimension 0..3", std::to_string(dim));
    const int64_t tag = cur.integer("physical tag");
    if (tag < std::numeric_limits<int>::min() || tag > std::numeric_limits<int>::max())
      cur.fail("a physical tag within the range of int", std::to_string(tag));
    mesh.name_group(static_cast<int>(dim), static_cast<int>(tag), cur.quoted("physical name"));
  }
  f.expect_end("$EndPhysicalNames");
}

TetMesh read_msh(const std::string& path, double scale, MshReadStats* stats, const InputFileLimit& limit,
                 size_t window_bytes) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw Error(path + ": expected a positive mesh scale, found " + std::to_string(scale));
  InputFileReader file(path, limit, "mesh file");
  TextCursor cur(file, path, window_bytes);
  // A path in a scene can name any file: one that is not a mesh at all is refused without a word of it.
  const std::string_view first = cur.token();
  if (first != "$MeshFormat")
    cur.fail(
        "a Gmsh MSH file, which starts with $MeshFormat",
        first.empty() ? "an empty file" : "a file that does not (not a Gmsh mesh; its content is not shown)");
  const MshFormat format = read_format(cur, file.size());
  MshFields fields(cur, format.binary, file.size());
  MshMeshBuilder mesh(fields, scale);
  const bool v41 = format.version == 41;
  for (std::string_view section = fields.token(); !section.empty(); section = fields.token()) {
    if (section.front() != '$') cur.fail("a section name such as $Nodes", TextCursor::describe(section));
    if (section == "$MeshFormat") {
      const int line = cur.line();
      if (!(read_format(cur, file.size()) == format))
        cur.fail_at(line, "the version and file type of the first $MeshFormat", "others");
    } else if (section == "$PhysicalNames") {
      read_msh_physical_names(fields, mesh);
    } else if (section == "$Entities" && v41) {
      read_msh41_entities(fields, mesh);
    } else if (section == "$Nodes") {
      if (mesh.have_nodes) cur.fail("one $Nodes section", "a second one");
      v41 ? read_msh41_nodes(fields, mesh) : read_msh22_nodes(fields, mesh);
      mesh.have_nodes = true;
    } else if (section == "$Elements") {
      if (!mesh.have_nodes) cur.fail("$Nodes before $Elements", "$Elements");
      if (mesh.have_elements) cur.fail("one $Elements section", "a second one");
      v41 ? read_msh41_elements(fields, mesh) : read_msh22_elements(fields, mesh);
      mesh.have_elements = true;
    } else if (section == "$PartitionedEntities") {
      cur.fail("an unpartitioned mesh", "$PartitionedEntities; save the mesh without partitions");
    } else {
      // Copied: skipping moves the window under the token's view. Binary data in a section skipped so
      // (a binary $NodeData) is scanned for its closing line like text.
      const std::string name(section);
      const std::string end = "$End" + name.substr(1);
      const int line = cur.line();
      if (!cur.skip_past_line_starting(end)) cur.fail_at(line, end + " closing " + name, "end of file");
    }
  }
  if (!mesh.have_nodes) cur.fail("a $Nodes section", "end of file");
  if (!mesh.have_elements) cur.fail("an $Elements section", "end of file");
  MshReadStats local;
  TetMesh result =
      mesh.finish(cur.content_hash(), &local);  // the hash of the whole file: parsing ended at its end
  if (stats) *stats = local;
  if (result.tets.empty()) {
    std::string found = "none";
    if (!local.skipped_elements.empty()) {
      found = "only other element types:";
      for (const auto& [type, n] : local.skipped_elements)
        found += " " + std::to_string(n) + " of type " + std::to_string(type);
      found += " (re-mesh with first-order tets: Mesh.ElementOrder = 1)";
    }
    throw Error(path + ": expected 4-node tetrahedra (element type 4), found " + found);
  }
  return result;
}

}  // namespace rift
