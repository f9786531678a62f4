#pragma once
// A movie file of a batch render's frames (an orbit, a time series): `-o NAME.mp4` (H.264 through
// libx264) or `NAME.webm` (VP9 through libvpx), with FFmpeg's libraries (libavformat muxes,
// libavcodec encodes, libswscale converts RGB to the codecs' 4:2:0 YUV). Frames are added in
// order, one per 1 / frame_rate seconds, and the file is complete after finish(). The batch render
// calls it on its writer thread (io/frame_writer.h), so encoding overlaps the next frame's render.
//
// yuv420p holds chroma at half resolution, so both sides must be even: an odd width or height is
// padded by one column or row that repeats the frame's last (the movie is then one pixel wider or
// taller than the frames; docs/usage.md says so).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sortlast {

// Whether `path` names a movie (.mp4, .webm; case-insensitive).
bool isMoviePath(const std::string& path);

class MovieWriter {
 public:
  // quality: the codec's constant rate factor, lower is better (H.264: 0-51, libx264's default
  // 23; VP9: 0-63, libvpx's constant-quality mode, 31 by default when unset). Throws InputError
  // naming `path` (an unknown container, an encoder this FFmpeg lacks, a quality out of range,
  // a file that cannot be opened).
  MovieWriter(std::string path, int width, int height, int frame_rate, std::optional<int> quality);
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // One opaque RGB frame, 8 bits a channel, row 0 at the top, of the size given at construction.
  void addFrame(const std::vector<uint8_t>& rgb);
  // Drains the encoder and writes the trailer; the file is complete after it.
  void finish();

  int encodedWidth() const;   // the width rounded up to even
  int encodedHeight() const;
  static int defaultQuality(const std::string& path);  // 23 (.mp4) or 31 (.webm)
  static int maxQuality(const std::string& path);      // 51 (.mp4) or 63 (.webm)
  static const char* encoderName(const std::string& path);  // libx264 or libvpx-vp9

 private:
  struct State;
  std::string path_;
  int width_, height_;
  std::unique_ptr<State> s_;
};

}  // namespace sortlast
