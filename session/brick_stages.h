#pragma once
// The brick stages of one rank's frame: draw (BrickRenderer::render, the GL work, timed by the
// GPU: draw_s), read-back (the brick's pixels from the GPU), encode (RLE, or the Emission format
// for glow) and exchange (the compositor takes the image; direct send starts sending it at once).
//
// Overlapped (render.pipeline: overlapped, the default): a volume brick's pixels are converted to
// RGBA8 on the GPU and read into a ring of pixel-buffer objects (render/gl/pixel_readback.h), and
// brick k+1's draw is issued before brick k's pixels are waited for, so the GPU draws while this
// core reads back, encodes and sends (paper 1's pipeline, on today's GL). Serial: each brick drawn,
// read back as floats, converted on the CPU and sent before the next — the pipeline before it,
// kept so a benchmark can run old and new side by side. Both give the same bytes.
#include <string>
#include <vector>

#include "common/camera.h"
#include "compositing/compositor.h"
#include "compositing/rect_image.h"
#include "render/brick_renderer.h"
#include "session/fault_injection.h"
#include "session/frame_stats.h"
#include "session/surface_gather.h"

namespace sortlast {

struct BrickStages {
  BrickRenderer& renderer;
  Compositor& compositor;
  const FrameFaults& faults;
  const std::vector<int>& ids;      // this rank's bricks, in the order they are drawn
  const std::vector<int>& handles;  // their renderer handles
  const Camera& cam;
  double spacing = 0, near_plane = 0, far_plane = 0;
  bool want_surface = false;
  bool glow = false;  // images in float, sent in the Emission format
  bool rle = true;
  bool overlapped = true;
  std::string dump_layers;  // also write each brick image here (bench_compositing --layers)
  // A projection (render.blend: mip, minip, average, additive): images in float, sent in this
  // format (compositing/projection_pixels.h); RGBA8: none.
  WireFormat projection = WireFormat::RGBA8;
};

// Every brick of this rank through the stages. Adds the stages' busy seconds (draw_s, render_s =
// the CPU's time issuing the draws, readback_s, encode_s, exchange_s) and the byte and brick
// counts to `st`; with want_surface, each brick's surface piece to `surfaces`. On an error no
// read-back is left in flight.
void runBrickStages(const BrickStages& b, RankFrameStats& st, std::vector<SurfacePiece>& surfaces);

}  // namespace sortlast
