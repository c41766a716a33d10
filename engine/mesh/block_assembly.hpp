#pragma once
// Several lattice blocks (engine/mesh/lattice_box.hpp) in one mesh, sharing no nodes: each block is a
// separate body. Block k is region blocks[k].name and its faces are the surfaces "<name>_xmin" ...
// "<name>_zmax". For contact scenes: a block on a base, two blocks colliding, stacks of blocks.
#include <vector>

#include "engine/mesh/tet_mesh.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

// Throws rift::Error when a block has no name or two blocks share one.
TetMesh generate_block_assembly(const std::vector<BlockSpec>& blocks);

}  // namespace rift
