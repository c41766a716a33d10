#pragma once
// `rift render RUN_DIR`: field pictures of a run, drawn headless by ParaView's Python (pvpython, under
// xvfb-run when there is no display): a plane cut coloured by a chosen field with the crack trace, and
// the broken joints coloured by the time each broke (engine/render/render_run.py says what and how).
#include <filesystem>
#include <string>
#include <vector>

namespace rift {

struct RenderOptions {
  std::filesystem::path out_dir;  // default RUN_DIR/pictures
  std::string field;              // NAME[:COMPONENT]; empty: the script's default
  std::string normal = "z";       // axis normal to the cut plane
  std::string at;                 // the plane's position along the normal in m; empty: the solid's centre
  std::string times = "last";     // "last", "all" or times in s separated by commas
  std::string size = "1280x960";  // pixels
  std::string range;              // "MIN,MAX" of the colour map in display units; empty: percentiles
};

struct RenderResult {
  std::vector<std::filesystem::path> pictures;  // written, in order
  std::string problem;                          // why nothing (or not everything) was drawn; empty on success
};

RenderResult render_run(const std::filesystem::path& run_dir, const RenderOptions& options);

}  // namespace rift
