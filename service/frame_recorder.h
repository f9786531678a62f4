#pragma once
// Recording the frames a service sends into one movie file (POST /api/record; docs/service.md):
// rank 0's frame loop hands each frame it answers to the recorder, which converts, fits and
// encodes it on a thread of its own (io/frame_writer.h, io/movie_writer.h), so the frame loop
// only waits when the encoder falls `kQueueFrames` frames behind. The movie takes the size of
// its first frame; a later frame of another size (a viewer resized, another client) is scaled
// to fit inside it, aspect kept, centred on the frame's background colour.
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "io/frame_writer.h"
#include "io/image.h"
#include "io/movie_writer.h"

namespace sortlast {

// Scales an opaque RGB image (w x h) to fit inside W x H, aspect kept (bilinear), centred on
// `background` (0..1). The same size: a copy.
std::vector<uint8_t> fitRGB8(const std::vector<uint8_t>& rgb, int w, int h, int W, int H,
                             const glm::dvec3& background);

class FrameRecorder {
 public:
  static constexpr size_t kQueueFrames = 4;  // frames waiting for the encoder (the writer holds one more)

  ~FrameRecorder();  // a recording still going is finished (the file stays playable)

  // From start() to stop(), also after a failed write (stop() reports it).
  bool recording() const { return active_; }
  const std::string& name() const { return name_; }
  // Starts a recording into `file` (an absolute path, already confined to the record directory;
  // `name`: as the client gave it). Throws InputError naming the problem (a frame rate outside
  // [1, 240], a quality outside the codec's range, a file that cannot be written).
  void start(const std::string& file, const std::string& name, int frame_rate, std::optional<int> quality);
  // The frame just answered (premultiplied RGBA over `background`). A failed encode or write
  // ends the recording; stop() then reports it.
  void add(ImageRGBA8 image, const glm::dvec3& background);
  // Finishes the movie (waits for the encoder, writes the trailer) and returns its facts: name,
  // frames, width, height, frames_scaled, encode_s, wait_s. Throws InputError for a failed encode
  // or write (the recording is over either way).
  nlohmann::json stop();
  int frames() const { return frames_; }

 private:
  std::string file_, name_;
  int frame_rate_ = 30;
  std::optional<int> quality_;
  int width_ = 0, height_ = 0;  // the movie's: its first frame's
  int frames_ = 0, scaled_ = 0;
  bool active_ = false;
  std::string failure_;         // a failed write, reported by stop()
  std::unique_ptr<FrameWriter> writer_;
  std::shared_ptr<std::unique_ptr<MovieWriter>> movie_;  // opened by the first frame's job
};

}  // namespace sortlast
