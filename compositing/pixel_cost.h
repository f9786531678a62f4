#pragma once
// Where the per-pixel work of compositing happens, named so that a simulated run can charge its
// cost. In the normal build chargePixels is an empty inline function and costs nothing. The SMPI
// build (docs/smpi.md: SimGrid runs the same strategy code on thousands of simulated hosts)
// defines SORTLAST_SMPI and links a definition that turns pixels into simulated seconds from
// per-pixel rates measured on a real machine (bench/scale/measure_rates.cpp), because SimGrid
// otherwise times the real loops on the one machine running every simulated rank, which is both
// slow and as noisy as that machine is busy.
//
// Each call site charges the pixels of one public image operation once (not the RLE or blend
// helpers inside it), so no pixel is counted twice.
#include <cstdint>

namespace sortlast {

enum class PixelWork : int {
  DecodeBlend8,      // a brick image's RLE stream decoded and blended over float (blendBackToFront)
  DecodeBlendInto8,  // the same over RGBA8, rounding at every blend (direct send, precision rgba8)
  BlendFloat,        // float layers blended into a new rectangle image (blendBackToFront of layers)
  Scan,              // the active rectangle of a float image (activeRect)
  Encode,            // float pixels rounded to the wire format and RLE-encoded (encodePart)
  Decode,            // a part decoded from the wire format to float (decodePart)
  DecodeRGBA8,       // a final RGBA8 part decoded into the frame (pastePart)
  Copy,              // float pixels copied or cleared (crop, pastePart, a new image's zero fill)
  Round8,            // float pixels rounded to RGBA8 (direct send's frame)
  Fill8,             // a new RGBA8 frame's zero fill (rank 0)
  Place,             // 4 bytes of a raw final part put in place in the frame (MPI's unpacking of a
                     // strided receive on rank 0: a copy of each row)
  Count
};

#ifdef SORTLAST_SMPI
// `bytes_per_pixel`: 4 (RGBA8) or 8 (RGBA16 / Emission) on the wire, where the format matters.
void chargePixels(PixelWork work, long long pixels, int bytes_per_pixel = 4);
#else
inline void chargePixels(PixelWork, long long, int = 4) {}
#endif

// Marks the moment this rank has finished its part of the swap rounds and starts the gather of
// the final parts to rank 0, so that a simulated run can tell what the gather adds to the frame
// (the frame's end minus the last rank's mark) from what the rounds take. Empty outside SMPI.
#ifdef SORTLAST_SMPI
void markGatherStart();
#else
inline void markGatherStart() {}
#endif

}  // namespace sortlast
