#pragma once
// The sections with a few plain keys each: image, camera orbit, bricks, time, limits. Their rows
// are in image.cpp, camera.cpp, bricks.cpp, time.cpp and limits.cpp beside this file.
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sortlast {

// image.* (image.width and image.height are the camera's: Camera carries the image size).
struct ImageSection {
  glm::dvec3 background{0.0};  // what the frame is composited over when written
};

// camera.orbit.*
struct OrbitSpec {
  int frames = 0;          // 0: a single view
  double elevation = 0;    // degrees
  double start = 0;        // degrees: the azimuth of the first frame
  std::optional<double> radius;
};

// bricks.*
struct BricksSection {
  int per_axis = 2;  // d: d x d x d bricks
};

// time.* and the series keys (volume.files, particles.files): one file per step, sorted;
// volume.file and particles.file then hold the file of `step`. Empty: no series (one step).
struct TimeSection {
  std::vector<std::string> volume_files, particle_files;
  int step = 0;
  int steps = 1;            // steps of the series (1 without one)
  double cache_mib = 1024;  // host memory per rank for cached steps (resident sessions)
};

// limits.*
struct LimitsSection {
  std::optional<double> memory_mib;  // unset: from MemAvailable
};

}  // namespace sortlast
