#pragma once
// A Cinema image database (spec A, "parametric-image-stack") of in-situ renders: for every fired
// step, one image per camera of a phi/theta sweep around the scene, and an info.json index that
// Cinema viewers browse. See docs/insitu_actions.md for the layout.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "insitu/actions.h"

namespace sortlast {

// The camera position of one view of the sweep: at the base camera's distance from look_at,
// phi degrees around `up` (right-handed, starting from the base camera's azimuth) and theta
// degrees of elevation above the plane perpendicular to `up`. Throws InputError if theta is not
// in (-90, 90) (at a pole the azimuth is lost and `up` is the view direction), if the base camera
// sits on look_at, or if up is zero.
glm::dvec3 cinemaPosition(const glm::dvec3& look_at, const glm::dvec3& base_position,
                          const glm::dvec3& up, double phi_deg, double theta_deg);

// The index of one render's database. Rank 0 owns it: after all images of a step are written it
// calls addStep, then write(), so info.json never lists an image that is not there.
class CinemaIndex {
 public:
  explicit CinemaIndex(CinemaSpec spec);

  const CinemaSpec& spec() const { return spec_; }
  // The image of one view, relative to the directory: "000010/90_-30.png".
  std::string imagePath(long long step, double phi, double theta) const;
  // Lists a step (replacing an earlier entry for the same step); `images` relative to the
  // directory, as imagePath gives them.
  void addStep(long long step, double time, const std::vector<std::string>& images);
  // (Re)writes DIRECTORY/info.json with every step added so far, atomically (a temporary file
  // renamed over it), so a viewer reading it meanwhile sees the old index or the new one. Creates
  // the directory. Throws InputError if it cannot.
  void write() const;

 private:
  struct StepEntry {
    long long step;
    double time;
    std::vector<std::string> images;
  };
  CinemaSpec spec_;
  std::vector<StepEntry> steps_;  // sorted by step
};

}  // namespace sortlast
