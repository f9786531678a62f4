// The adaptive section's keys: the paper's adaptive sampling (a multiresolution volume).
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::adaptiveKeys() {
  return {
    {"adaptive.tolerance", "0",
     "Adaptive sampling (the paper's section 4.2), in percent: each block of the volume is stored at the "
     "coarsest resolution (halved step by step, a coarse sample the mean of the fine cells "
     "around it) whose error stays within this: the block's squared error against the original "
     "(the paper's eq. 3) at most (tolerance/100)^2 x its sum of squared values, i.e. an RMS "
     "error of at most this percent of its RMS value. 0: off (the original samples; the "
     "preprocessing at 0 is lossless). See `sortlast adaptive-stats`. Above 0 "
     "the volume is rendered from the blocks, each sampled at its own resolution along the rays "
     "(needs `render.method: raycast`; its blocks replace `render.block_cells`), and every rank "
     "reads the whole volume to build them.",
     Real{member<&Scene::adaptive, &AdaptiveSection::tolerance>, {{"in [0, 100]", "must be {allowed} percent"}}}},
    {"adaptive.blocks", "8",
     "Adaptive sampling: b, the blocks per axis of the whole volume (the paper: 4, 8, 16). "
     "Blocks have the smallest power-of-two size s with b x s >= the "
     "cells per axis, so there may be fewer than b per axis; they do not depend on "
     "`bricks.per_axis`.",
     Int{member<&Scene::adaptive, &AdaptiveSection::blocks>,
         {{"a power of two in [1, 256]", "must be {allowed}, got {value}"}}}},
    {"adaptive.steps", "own",
     "Adaptive sampling, along the rays: `own` (a block at level L, whose samples are 2^L cells "
     "apart, is rendered at its own resolution: every 2^L-th sample of the ray lattice, each "
     "standing for 2^L steps) or `fine` (every block at every step: the adaptive field's "
     "accuracy at the full sampling cost, to tell what the data reduction costs from what the "
     "fewer samples cost).",
     Choice{member<&Scene::adaptive, &AdaptiveSection::steps>}},
  };
}
