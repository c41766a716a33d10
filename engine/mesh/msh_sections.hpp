#pragma once
// The readers of the sections of an MSH file that differ between format versions 4.1 (msh41_sections.cpp)
// and 2.2 (msh22_sections.cpp); each reads one section, from after its $Name line to its $EndName, into
// the mesh being built, from an ASCII or a binary file as `fields` says. Layouts: the "MSH file format"
// chapter of the Gmsh manual (4.1; 2.2 under the legacy formats).
#include "engine/mesh/msh_fields.hpp"
#include "engine/mesh/msh_mesh_builder.hpp"

namespace rift {

// $PhysicalNames: the same text in every version and file type.
void read_msh_physical_names(MshFields& fields, MshMeshBuilder& mesh);

void read_msh41_entities(MshFields& fields, MshMeshBuilder& mesh);
void read_msh41_nodes(MshFields& fields, MshMeshBuilder& mesh);
void read_msh41_elements(MshFields& fields, MshMeshBuilder& mesh);

void read_msh22_nodes(MshFields& fields, MshMeshBuilder& mesh);
void read_msh22_elements(MshFields& fields, MshMeshBuilder& mesh);

}  // namespace rift
