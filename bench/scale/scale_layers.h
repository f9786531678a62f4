#pragma once
// Synthetic brick images for compositing at any rank count (bench_scale, measure_rates): what P
// ranks of a kd-split would render of one volume, without rendering it.
//
// The unit cube is cut for P ranks the way sortlast's kd-split cuts bricks: recursively, along x,
// y, z in turn, into halves holding floor(n/2) and ceil(n/2) ranks, numbered low side first. The
// content is a sphere of uniform density centred in the cube, seen by an orthographic camera turned
// 20 degrees about y and 15 about x (so the ranks' screen rectangles overlap as real bricks' do);
// the frame is the square around the cube's projection. The sphere's radius is set by `coverage`,
// the fraction of the frame its disc covers (at most 0.5 with these angles: the sphere must fit in
// the cube). Rank r's image is its box's share of the sphere: alpha = 1 - exp(-sigma * length of
// the ray inside box and sphere), a whole diameter giving alpha 0.9, premultiplied, RGBA8.
// Ranks whose box misses the sphere have a transparent image, as in a real decomposition.
#include <vector>

#include "compositing/brick_image.h"
#include "common/visibility.h"

namespace sortlast::scale {

// The largest coverage a sphere inside the cube can have with this camera.
double maxCoverage();

// Every rank, far to near (the kd-tree traversed far side first); bricks: one per rank, id = rank.
VisibilityOrder sphereOrder(int ranks);

// Rank `rank`'s image of a width x height frame, RLE-encoded (`rle` false: runs of 1, as long as
// the raw pixels). Throws std::invalid_argument for a coverage outside (0, maxCoverage()].
// The rectangle rank `rank`'s image can cover, from geometry alone (its box's projection clipped
// to the sphere's disc), as a renderer forecasts a brick's rectangle from its box before rendering:
// what `compositing.strategy: auto` is given. The image's own rectangle lies inside it.
Rect sphereLayerBound(int rank, int ranks, int width, int height, double coverage);

BrickImage sphereLayer(int rank, int ranks, int width, int height, double coverage, bool rle);

}  // namespace sortlast::scale
