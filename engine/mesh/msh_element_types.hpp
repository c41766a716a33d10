#pragma once
// Nodes per element of Gmsh's element types (the "MSH file format" chapter of the Gmsh manual lists
// them): a binary MSH file gives an element's nodes without their count, so a record of a type the
// reader does not use can only be skipped when its size is known from the type.
namespace rift {

inline constexpr int kMshTriangle = 2;  // 3-node triangle
inline constexpr int kMshTet = 4;       // 4-node tetrahedron

// The number of nodes of Gmsh element type `type`; 0 for a type not in the table.
constexpr int msh_nodes_per_element(int type) {
  // Types 1 - 31: lines, triangles, quadrangles, tets, hexahedra, prisms, pyramids of orders 1 - 5 and
  // the point (15); 92, 93: the third- and fourth-order hexahedra.
  constexpr int kNodes[32] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                              8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
  if (type >= 1 && type <= 31) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

}  // namespace rift
