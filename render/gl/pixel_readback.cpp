#include "render/gl/pixel_readback.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sortlast {

PixelReadback::PixelReadback(const GlApi& gl, int slots) : gl_(gl), slots_(size_t(std::max(1, slots))) {
  for (Slot& s : slots_) gl_.GenBuffers(1, &s.buffer);
}

PixelReadback::~PixelReadback() {
  for (Slot& s : slots_) {
    if (s.mapped) {
      gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer);
      gl_.UnmapBuffer(GL_PIXEL_PACK_BUFFER);
    }
    if (s.fence) gl_.DeleteSync(s.fence);
    gl_.DeleteBuffers(1, &s.buffer);
  }
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

PendingPixels PixelReadback::start(const Rect& r, GLenum format, GLenum type, int pixel_bytes) {
  const int index = next_;
  Slot& s = slots_[size_t(index)];
  if (s.busy)
    throw std::logic_error("pixel read-back: all " + std::to_string(slots_.size()) +
                           " slots are in flight; release one first");
  s.bytes = size_t(r.area()) * size_t(pixel_bytes);
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer);
  if (s.bytes > s.capacity) {  // grows only: a steady orbit reuses the same storage
    gl_.BufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(s.bytes), nullptr, GL_STREAM_READ);
    s.capacity = s.bytes;
  }
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(r.x, r.y, r.w, r.h, format, type, nullptr);  // offset 0 of the bound buffer
  // Unbound at once: every other ReadPixels (float layers, surfaces) writes to client memory.
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  s.fence = gl_.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  s.busy = true;
  gl_.check("pixel read-back start");
  next_ = (next_ + 1) % int(slots_.size());
  return {this, index, r, pixel_bytes};
}

std::span<const uint8_t> PixelReadback::map(const PendingPixels& p) {
  if (p.ring != this || p.slot < 0 || p.slot >= int(slots_.size()) || !slots_[size_t(p.slot)].busy)
    throw std::logic_error("pixel read-back: map of a read that is not pending here");
  Slot& s = slots_[size_t(p.slot)];
  if (s.fence) {
    // The first wait flushes the commands before the fence (so a context that issued nothing
    // since cannot wait forever); one second at a time, so a lost device ends in an error.
    GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
    for (int waited = 0;; ++waited) {
      const GLenum r = gl_.ClientWaitSync(s.fence, flags, 1'000'000'000ull);
      if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) break;
      if (r == GL_WAIT_FAILED || waited >= 60)
        throw std::runtime_error("OpenGL: waiting for a brick's pixels failed (fence)");
      flags = 0;
    }
    gl_.DeleteSync(s.fence);
    s.fence = nullptr;
  }
  if (!s.mapped) {
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer);
    const void* data = s.bytes ? gl_.MapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(s.bytes), GL_MAP_READ_BIT)
                               : nullptr;
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (s.bytes && !data) throw std::runtime_error("OpenGL: mapping a read-back buffer failed");
    s.mapped = s.bytes > 0;
    s.data = data;
  }
  return {static_cast<const uint8_t*>(s.data), s.bytes};
}

void PixelReadback::release(PendingPixels& p) {
  if (p.ring != this || p.slot < 0 || p.slot >= int(slots_.size())) return;
  Slot& s = slots_[size_t(p.slot)];
  if (s.mapped) {
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer);
    gl_.UnmapBuffer(GL_PIXEL_PACK_BUFFER);
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  }
  if (s.fence) gl_.DeleteSync(s.fence);  // released unread (an abandoned frame)
  s.fence = nullptr;
  s.data = nullptr;
  s.mapped = s.busy = false;
  p = {};
}

int PixelReadback::inFlight() const {
  int n = 0;
  for (const Slot& s : slots_) n += s.busy;
  return n;
}

size_t PixelReadback::capacity() const {
  size_t n = 0;
  for (const Slot& s : slots_) n += s.capacity;
  return n;
}

}  // namespace sortlast
