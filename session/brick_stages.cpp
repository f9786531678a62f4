#include "session/brick_stages.h"

#include <mpi.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <span>

#include "common/error.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"
#include "compositing/projection_pixels.h"

namespace sortlast {

namespace {

void dumpLayer(const std::string& dir, const BrickImage& img) {
  std::vector<uint8_t> bytes = packBrickImage(img);
  std::ofstream out(dir + "/brick_" + std::to_string(img.brick_id) + ".bin", std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw InputError("cannot write brick image into " + dir);
}

// A drawn brick whose pixels may still be on their way; never moved (held by unique_ptr), so its
// read-back slot is released exactly once, also when a stage throws.
struct InFlight {
  int id = -1;
  BrickFrame frame;
  InFlight(int brick_id, BrickFrame f) : id(brick_id), frame(std::move(f)) {}
  ~InFlight() {
    if (frame.pending.pending()) frame.pending.ring->release(frame.pending);
    // (A brick left unread needs nothing: its image is overwritten by the next draw.)
  }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;
};

// Read-back, encode, exchange of one drawn brick.
void sendBrick(const BrickStages& b, InFlight& f, RankFrameStats& st, std::vector<SurfacePiece>& surfaces) {
  BrickFrame& bf = f.frame;
  BrickImage img{f.id, bf.rect, {}};
  const double t0 = MPI_Wtime();
  std::span<const uint8_t> px = bf.pixels.px;
  if (bf.pending.pending()) px = bf.pending.ring->map(bf.pending);
  const double t1 = MPI_Wtime();
  const bool projection = b.projection != WireFormat::RGBA8;
  const int pixel_bytes = b.glow || projection ? 8 : 4;  // glow: WireFormat::Emission
  const uint32_t max_run = b.rle ? kMaxRun : 1;
  const bool local = b.glow && b.compositor.takesLocalEmission() && b.dump_layers.empty();
  if (!bf.rect.empty() && projection)
    encodeProjected(b.projection, bf.pixels_f, img.rle, max_run);
  else if (!bf.rect.empty() && local)
    img.emission = std::move(bf.pixels_f);  // blended on this rank: not encoded
  else if (!bf.rect.empty() && b.glow)
    encodeEmission(bf.pixels_f, img.rle, max_run);
  else if (!bf.rect.empty())
    rleEncode(px, img.rle, 4, max_run);
  if (bf.pending.pending()) bf.pending.ring->release(bf.pending);
  const double t2 = MPI_Wtime();
  st.bytes_raw += double(bf.rect.area()) * pixel_bytes;
  st.bytes_rle += local ? double(bf.rect.area()) * pixel_bytes : double(img.rle.size());
  st.particle_rounds = std::max(st.particle_rounds, double(bf.particle_rounds));
  (bf.rect.empty() ? st.bricks_skipped : st.bricks_rendered) += 1;
  if (!b.dump_layers.empty()) dumpLayer(b.dump_layers, img);
  b.compositor.add(std::move(img));
  if (b.want_surface) surfaces.push_back({bf.rect, std::move(bf.surface)});
  st.readback_s += t1 - t0;
  st.encode_s += t2 - t1;
  st.exchange_s += MPI_Wtime() - t2;
  b.faults.afterBrick();
}

}  // namespace

void runBrickStages(const BrickStages& b, RankFrameStats& st, std::vector<SurfacePiece>& surfaces) {
  b.renderer.setOverlappedReadback(b.overlapped);
  std::unique_ptr<InFlight> previous;  // drawn, its pixels on their way
  for (size_t i = 0; i < b.ids.size(); ++i) {
    const double t0 = MPI_Wtime();
    auto drawn = std::make_unique<InFlight>(
        b.ids[i], b.renderer.render(b.handles[i], b.cam, b.spacing, b.near_plane, b.far_plane, b.want_surface));
    const double t1 = MPI_Wtime();
    b.renderer.readBack(drawn->frame);  // overlapped: started; serial: done
    st.render_s += t1 - t0;
    st.readback_s += MPI_Wtime() - t1;
    // Brick i's GL work is issued (and its read fenced): now wait for brick i - 1's pixels.
    if (previous) sendBrick(b, *previous, st, surfaces);
    previous = std::move(drawn);
    if (!b.overlapped) {  // serial: this brick's pixels are here already
      sendBrick(b, *previous, st, surfaces);
      previous.reset();
    }
  }
  if (previous) sendBrick(b, *previous, st, surfaces);
  st.draw_s += b.renderer.drawSeconds();  // every brick's pixels are back: the queries are done
}

}  // namespace sortlast
