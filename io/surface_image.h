#pragma once
// A surface image: per pixel, where the first surface along the pixel's ray is (distance t along
// the unit ray from the camera) and which way it faces (outward unit normal). It is what depth-
// aware comparisons of metaball renders work on: colour alone hides a surface that is in the
// wrong place but shaded alike. Stored as float, so t carries float precision (relative 6e-8).
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sortlast {

struct SurfaceImage {
  int width = 0, height = 0;
  std::vector<float> t;           // per pixel, row 0 = top; +infinity: no hit
  std::vector<glm::vec3> normal;  // outward unit normal where hit; (0, 0, 0) at misses
  SurfaceImage() = default;
  SurfaceImage(int w, int h);  // all misses
  // A NaN or infinite t (whatever a writer used for "nothing there") is a miss.
  bool hit(size_t i) const { return std::isfinite(t[i]); }
};

// OpenEXR, 32-bit float, channels t, nx, ny, nz (io/image_files.h);
// misses are stored as t = +inf. Throws InputError if the file cannot be written.
void writeSurfaceImage(const std::string& path, const SurfaceImage& img);
// Reads the channels by name, whatever their order in the file. Throws InputError on a missing or
// unreadable file, or one without channels t, nx, ny, nz.
SurfaceImage readSurfaceImage(const std::string& path);

}  // namespace sortlast
