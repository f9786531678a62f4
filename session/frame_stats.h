#pragma once
// Per-frame timings and byte counts, gathered from every rank to rank 0 and written as JSON
// (--stats FILE.json), one object per frame.
#include <mpi.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortlast {

struct RankFrameStats {
  double render_s = 0, encode_s = 0, transfer_s = 0;
  double bytes_raw = 0, bytes_rle = 0;  // RGBA8 bytes of the rectangles sent, before and after RLE
  double bricks_rendered = 0, bricks_skipped = 0;
  double peak_rss_mb = 0;
  double rss_mb = 0;  // resident memory now (VmRSS), at the end of the frame
  // Bytes malloc has handed out and not had back, at the end of the frame (mallinfo2): a leak's
  // direct signal, which the soak tests' slope reads. VmRSS also rises in steps when the allocator
  // or the GL driver takes a new block of pages and keeps it (measured: 1 MiB steps at requests
  // ~400 and ~830 of the service soak, flat afterwards), which a least-squares slope reads as growth.
  double heap_mb = 0;
  double particles_held = 0;   // particles this rank's bricks hold, ghosts included
  double particle_rounds = 0;  // most sample windows (rounds of passes) any of its bricks needed
  double bytes_sent = 0;       // compositing: bytes this rank sent, message headers included
  double strategy_code = 0;    // compositing.strategy auto: k of the radix-k it chose, 1 direct
  // The frame's stages on this rank (session/brick_stages.h): busy seconds of each; they may
  // overlap (the GPU draws while this core reads back and encodes), so they need not add up to
  // wall_s. render_s above is the CPU's time in the draw calls (serial: with the read-back).
  double draw_s = 0;      // GL work of the bricks (timer queries), read-back excluded
  // Reading the bricks' pixels: starting each read (overlapped: the GPU's conversion and a read
  // into the ring, which Mesa's llvmpipe does at once, waiting for the draw; serial: the whole
  // float read and the CPU's conversion), then waiting for and mapping them.
  double readback_s = 0;
  double exchange_s = 0;  // handing images to the compositor (direct send: sending them)
  double composite_s = 0; // the compositor's decode, blend and gather (CompositeStats)
  double wall_s = 0;      // this rank's frame, first brick to composited frame
};

// Gathers every rank's stats to rank 0 (empty vector elsewhere). Collective.
std::vector<RankFrameStats> gatherStats(const RankFrameStats& mine, MPI_Comm comm);

// Peak resident memory of this process so far, in MiB.
double peakRssMiB();
// Resident memory of this process now (VmRSS of /proc/self/status), in MiB; 0 if unreadable.
double currentRssMiB();
// Heap in use now (mallinfo2: arena bytes in use plus mmapped blocks), in MiB.
double heapInUseMiB();

// The frame's `stages` object: per rank each stage's busy seconds (arrays, as the other per-rank
// fields) and, for the frame: draw_s (the slowest rank's: the frame's GL time), the time outside
// it (total_s - draw_s) and its share, the stage that kept the slowest rank busy longest
// (`critical`), and how much its stages overlapped (their busy time beyond its wall time).
nlohmann::json stagesJson(const std::vector<RankFrameStats>& ranks, double total_s);

nlohmann::json frameJson(int frame, const std::vector<RankFrameStats>& ranks, double composite_s,
                         double total_s);

}  // namespace sortlast
