#include "compositing/rle.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "common/pixel_threads.h"

namespace sortlast {

namespace {

// Pixels of B bytes; alpha is the last B / 4 bytes.
template <size_t B>
bool transparent(const uint8_t* p) {
  for (size_t i = B - B / 4; i < B; ++i)
    if (p[i] != 0) return false;
  return true;
}

template <size_t B>
void encode(std::span<const uint8_t> px, std::vector<uint8_t>& out, uint32_t max_run) {
  const size_t n = px.size() / B;
  size_t i = 0;
  while (i < n) {
    if (!transparent<B>(&px[B * i])) {
      // Copy the whole stretch of visible pixels at once.
      size_t j = i + 1;
      while (j < n && !transparent<B>(&px[B * j])) ++j;
      out.insert(out.end(), px.begin() + B * i, px.begin() + B * j);
      i = j;
      continue;
    }
    size_t j = i + 1;
    while (j < n && transparent<B>(&px[B * j]) && j - i < max_run) ++j;
    uint32_t run = uint32_t(j - i);
    uint8_t marker[B] = {uint8_t(run & 0xff), uint8_t((run >> 8) & 0xff),
                         uint8_t((run >> 16) & 0xff)};
    out.insert(out.end(), marker, marker + B);
    i = j;
  }
}

// kWrite false: only the checks, with the same messages (what rleSplit reports a bad stream by).
template <size_t B, bool kWrite = true>
void decode(std::span<const uint8_t> s, size_t pixel_count, std::span<uint8_t> out) {
  if (kWrite && out.size() < B * pixel_count) throw RleError("RLE decode: output buffer too small");
  if (s.size() % B != 0)
    throw RleError("RLE decode: stream length " + std::to_string(s.size()) +
                   " is not a multiple of " + std::to_string(B));
  size_t o = 0;  // pixels written
  for (size_t i = 0; i < s.size(); i += B) {
    if (!transparent<B>(&s[i])) {
      if (o >= pixel_count) throw RleError("RLE decode: stream holds more pixels than the image");
      if constexpr (kWrite) std::memcpy(&out[B * o], &s[i], B);
      ++o;
      continue;
    }
    size_t run = size_t(s[i]) | size_t(s[i + 1]) << 8 | size_t(s[i + 2]) << 16;
    if (run == 0) throw RleError("RLE decode: zero-length run at byte " + std::to_string(i));
    if (run > pixel_count - o)
      throw RleError("RLE decode: run of " + std::to_string(run) + " at byte " + std::to_string(i) +
                     " overflows the image (" + std::to_string(pixel_count - o) + " pixels left)");
    if constexpr (kWrite) std::memset(&out[B * o], 0, B * run);
    o += run;
  }
  if (o != pixel_count)
    throw RleError("RLE decode: stream holds " + std::to_string(o) + " pixels, image has " +
                   std::to_string(pixel_count));
}

// Inputs below two parts' worth stay serial. 64 K pixels (256 KB of RGBA8) take about 0.07 ms
// to encode and 0.04 ms to decode on one core of the 2-core development machine (bench/pixels:
// 1.05 and 0.70 ms a 1024^2 frame). Not tuned by a sweep.
constexpr size_t kRleGrain = size_t(1) << 16;

// Parallel encoding. Each part [b, e) of the pixels is split into its leading transparent
// pixels, its middle (first visible pixel to last visible pixel) and its trailing transparent
// pixels. A middle starts and ends on a visible pixel, so the serial encoder gives it the same
// bytes it gives those pixels inside the whole image (its runs start and stop where the whole
// image's do). The transparent pixels around the cuts are joined into one run per gap and split
// into max_run pieces from its start, as the serial greedy encoder splits it.
template <size_t B>
void encodeParallel(std::span<const uint8_t> px, std::vector<uint8_t>& out, uint32_t max_run,
                    int parts) {
  const size_t n = px.size() / B;
  struct Part {
    size_t lead = 0, trail = 0;
    bool empty = true;  // all transparent
  };
  // The parts' streams, kept by the calling thread from call to call so a frame's encoding
  // allocates nothing once the first frame has sized them.
  thread_local std::vector<std::vector<uint8_t>> scratch;
  if (scratch.size() < size_t(parts)) scratch.resize(size_t(parts));
  std::vector<std::vector<uint8_t>>& middles = scratch;
  std::vector<Part> info(static_cast<size_t>(parts));
  parallelParts(parts, [&](int p) {
    const auto [b, e] = partRange(n, parts, p);
    Part& part = info[size_t(p)];
    std::vector<uint8_t>& mid = middles[size_t(p)];
    mid.clear();
    size_t v0 = b;
    while (v0 < e && transparent<B>(&px[B * v0])) ++v0;
    part.lead = v0 - b;
    if (v0 == e) return;
    size_t v1 = e;
    while (transparent<B>(&px[B * (v1 - 1)])) --v1;  // stops at v0 at the latest
    part.trail = e - v1;
    part.empty = false;
    encode<B>(px.subspan(B * v0, B * (v1 - v0)), mid, max_run);
  });
  auto runBytes = [&](size_t run) { return B * ((run + max_run - 1) / max_run); };
  std::vector<size_t> at(static_cast<size_t>(parts), 0);  // where each middle goes, from the start of the append
  size_t run = 0, total = 0;
  for (int p = 0; p < parts; ++p) {
    const Part& part = info[size_t(p)];
    run += part.lead;
    if (part.empty) continue;
    total += runBytes(run);
    at[size_t(p)] = total;
    total += middles[size_t(p)].size();
    run = part.trail;
  }
  total += runBytes(run);
  const size_t base = out.size();
  out.resize(base + total);
  uint8_t* o = out.data() + base;
  auto markers = [&](size_t len) {
    while (len > 0) {
      const uint32_t r = uint32_t(std::min<size_t>(len, max_run));
      uint8_t m[B] = {uint8_t(r & 0xff), uint8_t((r >> 8) & 0xff), uint8_t((r >> 16) & 0xff)};
      std::memcpy(o, m, B);
      o += B;
      len -= r;
    }
  };
  run = 0;
  for (int p = 0; p < parts; ++p) {
    const Part& part = info[size_t(p)];
    run += part.lead;
    if (part.empty) continue;
    markers(run);
    o += middles[size_t(p)].size();  // copied below
    run = part.trail;
  }
  markers(run);
  parallelParts(parts, [&](int p) {
    const std::vector<uint8_t>& mid = middles[size_t(p)];
    if (!info[size_t(p)].empty) std::memcpy(out.data() + base + at[size_t(p)], mid.data(), mid.size());
  });
}

// Pixels that the stream elements [0, count) decode to; `zero_run` set if a marker holds 0.
// Branch-free over whole words, so it vectorises: about a tenth of the decode's time.
template <size_t B>
size_t countPixels(const uint8_t* s, size_t count, bool& zero_run) {
  uint64_t pixels = 0;
  uint32_t zero = 0;
  for (size_t i = 0; i < count; ++i) {
    uint32_t lo, hi;
    std::memcpy(&lo, s + B * i, 4);
    std::memcpy(&hi, s + B * i + B - 4, 4);
    const uint32_t marker = uint32_t((hi >> (32 - 8 * (B / 4))) == 0);  // the last B / 4 bytes 0
    const uint32_t run = lo & 0xffffffu;
    pixels += marker ? run : 1u;
    zero |= marker & uint32_t(run == 0);
  }
  zero_run = zero != 0;
  return size_t(pixels);
}

template <size_t B>
std::vector<RlePiece> split(std::span<const uint8_t> s, size_t pixel_count, int parts) {
  const size_t elements = s.size() / B;
  std::vector<RlePiece> pieces(size_t(std::max(parts, 1)));
  std::vector<uint8_t> zero(pieces.size(), 0);
  std::vector<size_t> counts(pieces.size(), 0);
  if (s.size() % B == 0)
    parallelParts(int(pieces.size()), [&](int p) {
      const auto [b, e] = partRange(elements, int(pieces.size()), p);
      pieces[size_t(p)].byte_begin = B * b;
      pieces[size_t(p)].byte_end = B * e;
      bool z = false;
      counts[size_t(p)] = countPixels<B>(s.data() + B * b, e - b, z);
      zero[size_t(p)] = z;
    });
  size_t total = 0;
  bool bad = s.size() % B != 0;
  for (size_t p = 0; p < pieces.size(); ++p) {
    pieces[p].pixel_begin = total;
    total += counts[p];
    bad = bad || zero[p];
  }
  if (bad || total != pixel_count) {
    decode<B, false>(s, pixel_count, {});  // throws the serial decoder's message
    throw std::logic_error("RLE split: a stream failed the count but passed the decoder's checks");
  }
  return pieces;
}

void checkPixelBytes(int pixel_bytes) {
  if (pixel_bytes != 4 && pixel_bytes != 8 && pixel_bytes != 12)
    throw std::invalid_argument("RLE: pixels are 4, 8 or 12 bytes, not " + std::to_string(pixel_bytes));
}

}  // namespace

void rleEncode(std::span<const uint8_t> px, std::vector<uint8_t>& out, int pixel_bytes,
               uint32_t max_run) {
  checkPixelBytes(pixel_bytes);
  if (max_run < 1 || max_run > kMaxRun)
    throw std::invalid_argument("RLE: max_run must be in [1, 2^24 - 1]");
  const int parts = pixelParts(px.size() / size_t(pixel_bytes), kRleGrain);
  if (pixel_bytes == 4)
    parts > 1 ? encodeParallel<4>(px, out, max_run, parts) : encode<4>(px, out, max_run);
  else if (pixel_bytes == 8)
    parts > 1 ? encodeParallel<8>(px, out, max_run, parts) : encode<8>(px, out, max_run);
  else
    parts > 1 ? encodeParallel<12>(px, out, max_run, parts) : encode<12>(px, out, max_run);
}

std::vector<uint8_t> rleEncode(std::span<const uint8_t> px, int pixel_bytes, uint32_t max_run) {
  std::vector<uint8_t> out;
  out.reserve(px.size() / 8);
  rleEncode(px, out, pixel_bytes, max_run);
  return out;
}

void rleDecode(std::span<const uint8_t> s, size_t pixel_count, std::span<uint8_t> out,
               int pixel_bytes) {
  checkPixelBytes(pixel_bytes);
  const int parts = pixelParts(pixel_count, kRleGrain);
  if (parts <= 1) {
    if (pixel_bytes == 4)
      decode<4>(s, pixel_count, out);
    else if (pixel_bytes == 8)
      decode<8>(s, pixel_count, out);
    else
      decode<12>(s, pixel_count, out);
    return;
  }
  const size_t b = size_t(pixel_bytes);
  if (out.size() < b * pixel_count) throw RleError("RLE decode: output buffer too small");
  const std::vector<RlePiece> pieces = rleSplit(s, pixel_count, pixel_bytes, parts);
  parallelParts(int(pieces.size()), [&](int p) {
    rleVisit(
        s, pieces[size_t(p)], pixel_bytes,
        [&](size_t o, const uint8_t* px, size_t n) { std::memcpy(&out[b * o], px, b * n); },
        [&](size_t o, size_t n) { std::memset(&out[b * o], 0, b * n); });
  });
}

std::vector<RlePiece> rleSplit(std::span<const uint8_t> s, size_t pixel_count, int pixel_bytes,
                               int parts) {
  checkPixelBytes(pixel_bytes);
  if (pixel_bytes == 4) return split<4>(s, pixel_count, parts);
  return pixel_bytes == 8 ? split<8>(s, pixel_count, parts) : split<12>(s, pixel_count, parts);
}

}  // namespace sortlast
