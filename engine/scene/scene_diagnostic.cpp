#include "engine/scene/scene_diagnostic.hpp"

namespace rift {

std::string SceneDiagnostic::format() const {
  std::string out = file;
  if (line > 0) {
    out += ":" + std::to_string(line);
    if (column > 0) out += ":" + std::to_string(column);
  }
  out += ": ";
  if (!key_path.empty()) out += key_path + ": ";
  out += "expected " + expected + ", found " + found;
  if (!hint.empty()) out += " (" + hint + ")";
  return out;
}

}  // namespace rift
