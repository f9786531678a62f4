#include "session/frame_footprint.h"

#include "compositing/rect_image.h"

namespace sortlast {

FrameFootprint forecastFootprint(const SessionLayout& layout, const Camera& cam, int ranks) {
  FrameFootprint fp;
  fp.rect.assign(size_t(ranks), Rect{});
  fp.brick_pixels.assign(size_t(ranks), 0.0);
  fp.bricks.assign(size_t(ranks), 0);
  const int d = int(layout.planes[0].size()) - 1;
  const std::vector<int>& owner = layout.assignment.owner;
  for (int id = 0; id < int(owner.size()); ++id) {
    const int r = owner[size_t(id)];
    if (r < 0 || r >= ranks || d < 1) continue;
    const glm::ivec3 cell{id % d, id / d % d, id / (d * d)};
    const Rect rc = screenRectOf(cam, brickBox(layout.planes, cell));
    ++fp.bricks[size_t(r)];
    if (rc.empty()) continue;
    fp.rect[size_t(r)] = unionOf(fp.rect[size_t(r)], rc);
    fp.brick_pixels[size_t(r)] += double(rc.area());
  }
  return fp;
}

}  // namespace sortlast
