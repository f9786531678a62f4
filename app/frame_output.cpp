#include "app/frame_output.h"

#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "session/frame_legend.h"

namespace sortlast {

FrameOutput::FrameOutput(std::string output, const Scene& scene, int frames, FrameWriter& writer)
    : output_(std::move(output)),
      frames_(frames),
      background_(scene.image.background),
      legend_(scene.image.legend),
      movie_spec_(scene.image.movie),
      movie_(isMoviePath(output_)),
      writer_(writer),
      movie_writer_(std::make_shared<std::unique_ptr<MovieWriter>>()) {
  if (legend_.enabled() && std::filesystem::path(output_).extension() == ".exr")
    throw InputError("scene key 'image.legend.position': a legend is drawn into 8-bit frames; " +
                     output_ + " is a float (.exr) file");
  if (movie_ && movie_spec_.quality) {
    const double q = *movie_spec_.quality;
    if (q != std::floor(q))
      throw InputError("scene key 'movie.quality': a CRF is a whole number (got " + std::to_string(q) + ")");
    if (q > MovieWriter::maxQuality(output_))
      throw InputError("scene key 'movie.quality': " + std::to_string(int(q)) + " is outside " +
                       MovieWriter::encoderName(output_) + "'s CRF range [0, " +
                       std::to_string(MovieWriter::maxQuality(output_)) + "] (" + output_ + ")");
  }
}

void FrameOutput::push(int f, ImageRGBA8 image, const TransferFunction& tf) {
  const LegendSpec legend = legend_;
  const glm::dvec3 bg = background_;
  if (!movie_) {
    const std::string file = frameFileName(output_, f, frames_);
    writer_.push(file, [file, bg, legend, tf, image = std::move(image)]() mutable {
      if (legend.enabled()) drawLegend(image, tf, legend, bg);
      writeImage(file, image, bg);
    });
    return;
  }
  const std::string file = output_;
  const MovieSpec spec = movie_spec_;
  writer_.push(file, [file, bg, legend, tf, spec, movie = movie_writer_, image = std::move(image)]() mutable {
    if (legend.enabled()) drawLegend(image, tf, legend, bg);
    if (!*movie) {
      std::optional<int> q;
      if (spec.quality) q = int(*spec.quality);
      *movie = std::make_unique<MovieWriter>(file, image.width, image.height, spec.frame_rate, q);
    }
    (*movie)->addFrame(opaqueRGB8(image, bg));
  });
}

void FrameOutput::push(int f, ImageF image) {
  const std::string file = frameFileName(output_, f, frames_);
  const glm::dvec3 bg = background_;
  writer_.push(file, [file, bg, image = std::move(image)] { writeImage(file, image, bg); });
}

void FrameOutput::close() {
  if (!movie_) return;
  writer_.push(output_, [movie = movie_writer_] {
    if (*movie) (*movie)->finish();
  });
}

}  // namespace sortlast
