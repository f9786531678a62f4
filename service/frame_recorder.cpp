#include "service/frame_recorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "common/error.h"

namespace sortlast {

std::vector<uint8_t> fitRGB8(const std::vector<uint8_t>& rgb, int w, int h, int W, int H,
                             const glm::dvec3& background) {
  if (w == W && h == H) return rgb;
  std::vector<uint8_t> out(size_t(W) * H * 3);
  uint8_t bg[3];
  for (int c = 0; c < 3; ++c) bg[c] = uint8_t(std::lround(std::clamp(background[c], 0.0, 1.0) * 255.0));
  for (size_t p = 0; p < size_t(W) * H; ++p) std::copy(bg, bg + 3, &out[3 * p]);
  const double s = std::min(double(W) / w, double(H) / h);  // output pixels per input pixel
  const int fw = std::clamp(int(std::lround(w * s)), 1, W), fh = std::clamp(int(std::lround(h * s)), 1, H);
  const int x0 = (W - fw) / 2, y0 = (H - fh) / 2;
  for (int y = 0; y < fh; ++y) {
    // The output pixel's centre in input pixels, clamped to the outer samples' centres.
    const double sy = std::clamp((y + 0.5) * h / fh - 0.5, 0.0, double(h - 1));
    const int iy = std::min(int(sy), h - 2 < 0 ? 0 : h - 2);
    const double ty = h > 1 ? sy - iy : 0.0;
    for (int x = 0; x < fw; ++x) {
      const double sx = std::clamp((x + 0.5) * w / fw - 0.5, 0.0, double(w - 1));
      const int ix = std::min(int(sx), w - 2 < 0 ? 0 : w - 2);
      const double tx = w > 1 ? sx - ix : 0.0;
      const int ix1 = std::min(ix + 1, w - 1), iy1 = std::min(iy + 1, h - 1);
      uint8_t* o = &out[(size_t(y0 + y) * W + x0 + x) * 3];
      for (int c = 0; c < 3; ++c) {
        auto at = [&](int px, int py) { return double(rgb[(size_t(py) * w + px) * 3 + c]); };
        const double v = (1 - ty) * ((1 - tx) * at(ix, iy) + tx * at(ix1, iy)) +
                         ty * ((1 - tx) * at(ix, iy1) + tx * at(ix1, iy1));
        o[c] = uint8_t(std::lround(std::clamp(v, 0.0, 255.0)));
      }
    }
  }
  return out;
}

FrameRecorder::~FrameRecorder() {
  if (!recording()) return;
  try {
    stop();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sortlast serve: recording %s: %s\n", name_.c_str(), e.what());
  }
}

void FrameRecorder::start(const std::string& file, const std::string& name, int frame_rate,
                          std::optional<int> quality) {
  if (recording()) throw std::logic_error("FrameRecorder::start while recording");
  if (frame_rate < 1 || frame_rate > 240)
    throw InputError("frame_rate " + std::to_string(frame_rate) + " is outside [1, 240]");
  if (quality && (*quality < 0 || *quality > MovieWriter::maxQuality(file)))
    throw InputError("quality " + std::to_string(*quality) + " is outside " + MovieWriter::encoderName(file) +
                     "'s CRF range [0, " + std::to_string(MovieWriter::maxQuality(file)) + "]");
  if (!isMoviePath(file)) throw InputError("\"" + name + "\": a recording is a .mp4 or .webm file");
  // Opened now, so a file that cannot be written is refused here rather than at the first frame.
  if (!std::ofstream(file, std::ios::binary | std::ios::trunc))
    throw InputError("\"" + name + "\": cannot be opened for writing");
  file_ = file;
  name_ = name;
  frame_rate_ = frame_rate;
  quality_ = quality;
  width_ = height_ = frames_ = scaled_ = 0;
  failure_.clear();
  movie_ = std::make_shared<std::unique_ptr<MovieWriter>>();
  writer_ = std::make_unique<FrameWriter>(kQueueFrames);
  active_ = true;
}

void FrameRecorder::add(ImageRGBA8 image, const glm::dvec3& background) {
  if (!writer_ || image.width <= 0 || image.height <= 0) return;
  if (frames_ == 0) width_ = image.width, height_ = image.height;
  const bool scale = image.width != width_ || image.height != height_;
  scaled_ += scale;
  ++frames_;
  const int W = width_, H = height_, rate = frame_rate_;
  const std::optional<int> q = quality_;
  try {
    writer_->push(file_, [file = file_, movie = movie_, W, H, rate, q, background, image = std::move(image)] {
      std::vector<uint8_t> rgb = fitRGB8(opaqueRGB8(image, background), image.width, image.height, W, H, background);
      if (!*movie) *movie = std::make_unique<MovieWriter>(file, W, H, rate, q);
      (*movie)->addFrame(rgb);
    });
  } catch (const InputError& e) {  // an earlier frame's encode or write failed: the recording ends
    failure_ = e.what();
    std::fprintf(stderr, "sortlast serve: recording %s stopped: %s\n", name_.c_str(), e.what());
    writer_.reset();  // drops what waits, joins the thread
    movie_.reset();
  }
}

nlohmann::json FrameRecorder::stop() {
  nlohmann::json j = {{"name", name_}, {"frames", frames_}, {"width", width_}, {"height", height_},
                      {"frames_scaled", scaled_}};
  if (!active_) throw std::logic_error("FrameRecorder::stop while not recording");
  active_ = false;
  std::unique_ptr<FrameWriter> writer = std::move(writer_);
  auto movie = std::move(movie_);
  if (!failure_.empty()) throw InputError("the recording failed: " + failure_);
  writer->push(file_, [movie] {
    if (*movie) (*movie)->finish();
  });
  writer->finish();  // throws the first failure
  const FrameWriter::Stats st = writer->stats();
  j["encode_s"] = st.write_s;
  j["wait_s"] = st.wait_s;
  if (movie && *movie) j["width"] = (*movie)->encodedWidth(), j["height"] = (*movie)->encodedHeight();
  return j;
}

}  // namespace sortlast
