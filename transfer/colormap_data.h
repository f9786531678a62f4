#pragma once
// The files of transfer/colormaps/ (ParaView colour-map presets), compiled in: the build generates
// the definition (cmake/embed_colormaps.cmake), so the program needs no data directory at run
// time and the files stay what a user can open in ParaView and diff against its own presets.
#include <vector>

namespace sortlast {

struct EmbeddedColourMap {
  const char* stem;  // file name without ".json": the map's lowercase alias
  const char* json;  // the file's text
};

// In file-name order.
const std::vector<EmbeddedColourMap>& embeddedColourMaps();

}  // namespace sortlast
