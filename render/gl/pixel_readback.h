#pragma once
// Read-back without stalls: brick rectangles travel from the GPU into a ring of pixel-buffer
// objects, each read fenced, so the caller can issue the next brick's draw before it waits for
// this brick's pixels (paper 1 overlapped read-back with rendering the same way). A read is
// started (ReadPixels into the next slot's buffer, then a fence), later mapped (the wait: the
// fence, then MapBufferRange) and released (unmapped, the slot free again). Slots keep their
// buffers across bricks and frames; a slot grows when a larger rectangle comes (an image resized
// mid-orbit) and never shrinks, so a steady orbit allocates nothing.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/camera.h"
#include "render/gl/gl_api.h"

namespace sortlast {

class PixelReadback;

// A read under way: its ring, slot and rectangle. Default: nothing pending.
struct PendingPixels {
  PixelReadback* ring = nullptr;
  int slot = -1;
  Rect rect;
  int pixel_bytes = 0;
  bool pending() const { return ring != nullptr; }
};

class PixelReadback {
 public:
  explicit PixelReadback(const GlApi& gl, int slots = 3);
  ~PixelReadback();
  PixelReadback(const PixelReadback&) = delete;
  PixelReadback& operator=(const PixelReadback&) = delete;

  // ReadPixels of `r` from the bound read framebuffer (format, type: pixel_bytes a pixel, rows
  // packed) into the next slot, then a fence; returns at once. Throws std::logic_error if that
  // slot is still in flight (more reads pending than slots: the caller's pipeline is too deep).
  PendingPixels start(const Rect& r, GLenum format, GLenum type, int pixel_bytes);
  // Waits for the read's fence and maps its slot: r.w * r.h * pixel_bytes bytes, window row r.y
  // first (image row r.y: the projection flips y), valid until release(). Throws
  // std::runtime_error if the wait fails.
  std::span<const uint8_t> map(const PendingPixels& p);
  // Unmaps (if mapped) and frees the slot; `p` becomes empty.
  void release(PendingPixels& p);

  int slots() const { return int(slots_.size()); }
  int inFlight() const;
  // Bytes of buffer storage the ring holds (its slots' capacities).
  size_t capacity() const;

 private:
  struct Slot {
    unsigned buffer = 0;
    size_t capacity = 0, bytes = 0;
    GLsync fence = nullptr;
    const void* data = nullptr;  // while mapped
    bool busy = false, mapped = false;
  };
  const GlApi& gl_;
  std::vector<Slot> slots_;
  int next_ = 0;
};

}  // namespace sortlast
