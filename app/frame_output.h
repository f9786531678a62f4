#pragma once
// Where a batch render's frames go (rank 0): one image file per frame (frameFileName), or all of
// them into one movie (-o NAME.mp4 / NAME.webm; io/movie_writer.h), each with the colour legend
// drawn in when image.legend asks for one (session/frame_legend.h). Everything runs as jobs on
// the render's writer thread (io/frame_writer.h), so legend, encoding and writing overlap the
// next frame's render.
#include <memory>
#include <string>

#include "io/frame_writer.h"
#include "io/image.h"
#include "io/movie_writer.h"
#include "scene/scene.h"
#include "transfer/transfer_function.h"

namespace sortlast {

class FrameOutput {
 public:
  // Throws InputError for an output the scene cannot have (a legend in a float .exr file).
  FrameOutput(std::string output, const Scene& scene, int frames, FrameWriter& writer);
  // Frame f of the 8-bit or the float image; `tf`: the transfer function it was rendered with.
  void push(int f, ImageRGBA8 image, const TransferFunction& tf);
  void push(int f, ImageF image);
  // Hands over the movie's end (its trailer), if it is one; call before writer.finish().
  void close();
  bool movie() const { return movie_; }

 private:
  std::string output_;
  int frames_;
  glm::dvec3 background_;
  LegendSpec legend_;
  MovieSpec movie_spec_;
  bool movie_;
  FrameWriter& writer_;
  std::shared_ptr<std::unique_ptr<MovieWriter>> movie_writer_;  // opened by the first frame's job
};

}  // namespace sortlast
