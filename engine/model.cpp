#include "engine/model.hpp"

#include "engine/core/error.hpp"

namespace rift {

void Model::take_share(const SplitJob&, std::span<const SplitDomain>) {
  throw Error(
      "the " + name() +
      " model does not run split between processes yet (docs/distributed.md, \"Order of the work\"): run "
      "this scene on one process, with threads");
}

}  // namespace rift
