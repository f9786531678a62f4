#pragma once
// Images in memory: premultiplied RGBA, row 0 at the top. RGBA8 is what travels between ranks
// (the paper's intermediate image format); float images are for the reference and EXR output.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace sortlast {

struct ImageRGBA8 {
  int width = 0, height = 0;
  std::vector<uint8_t> px;  // 4 bytes per pixel
  ImageRGBA8() = default;
  ImageRGBA8(int w, int h) : width(w), height(h), px(size_t(w) * h * 4, 0) {}
  uint8_t* at(int x, int y) { return &px[(size_t(y) * width + x) * 4]; }
  const uint8_t* at(int x, int y) const { return &px[(size_t(y) * width + x) * 4]; }
};

struct ImageF {
  int width = 0, height = 0;
  std::vector<float> px;  // 4 floats per pixel
  ImageF() = default;
  ImageF(int w, int h) : width(w), height(h), px(size_t(w) * h * 4, 0.0f) {}
};

// Round a premultiplied float pixel to RGBA8, keeping colour <= alpha so the result is still a
// valid premultiplied pixel (and A = 0 implies RGB = 0, which the RLE codec relies on).
void toRGBA8(const float* in, uint8_t* out);
// `pixels` pixels (4 floats each in, 4 bytes each out), each exactly as above, on the pixel
// threads (common/pixel_threads.h): what a read-back brick image goes through.
void toRGBA8(const float* in, uint8_t* out, size_t pixels);
ImageRGBA8 toRGBA8(const ImageF& img);
ImageF toFloat(const ImageRGBA8& img);

// The premultiplied image composited over `background`: opaque RGB floats, 3 per pixel. Shared by
// writeImage and encodeImage (io/image_encode.h) so a file and a served frame look the same.
std::vector<float> overBackground(const ImageF& img, const glm::dvec3& background);

// Opaque RGB floats (overBackground's) rounded to 8 bits as every PNG and served frame is: round
// half away from zero after scaling by 255, then clamp (NaN: 0).
std::vector<uint8_t> toRGB8(const std::vector<float>& rgb);
// toRGB8(overBackground(toFloat(img), background)) bit for bit, in one pass without the float
// frame: what an 8-bit frame file and a served frame hold.
std::vector<uint8_t> opaqueRGB8(const ImageRGBA8& img, const glm::dvec3& background);

// Writes PNG, JPEG (quality kJpegFileQuality), binary PPM (8-bit) or EXR (float) by extension
// (io/image_files.h). The premultiplied image is composited over `background` and written opaque.
// Throws InputError naming the file on failure.
void writeImage(const std::string& path, const ImageF& img, const glm::dvec3& background);
void writeImage(const std::string& path, const ImageRGBA8& img, const glm::dvec3& background);
constexpr int kJpegFileQuality = 95;
// Throws InputError naming `path` when writeImage has no writer for its extension: a job checks
// its output name before it renders anything.
void checkOutputFormat(const std::string& path);
// Output file of frame i: OUT itself for a single frame, OUT with _0000 before the extension
// for a series (batch render, reference, in-situ outputs).
std::string frameFileName(const std::string& out, int frame, int frames);

// Reads a PNG, JPEG, PPM or EXR image as RGBA8 (an opaque RGB file gets A = 255).
ImageRGBA8 readImageRGBA8(const std::string& path);

// An image file's channels as stored, converted to float with no rounding for float files: any
// channel count (RGB frames, surface images' t, nx, ny, nz; R, G, B, A first); 8-bit files as
// value / 255 in four channels R, G, B, A. For comparisons in float.
struct ImageChannels {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> names;  // channel names as the file gives them
  std::vector<float> px;           // `channels` floats per pixel, row 0 at the top
};
ImageChannels readImageChannels(const std::string& path);

}  // namespace sortlast
