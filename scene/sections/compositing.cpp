// The compositing section's keys: how brick images reach rank 0: strategy, the network auto
// assumes, precision, RLE.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::compositingKeys() {
  return {
    {"compositing.strategy", "direct",
     "How brick images reach rank 0: `direct` (every brick image to rank 0, which blends them "
     "all), `binary-swap` (each rank blends its own bricks, then pairs of ranks swap halves of "
     "their image for log2 P rounds and rank 0 gathers the pieces), `radix-k` (the same with "
     "`compositing.radix` partners per round) or `auto` (each frame, whichever of direct and "
     "radix-k with k = 2, 4, 8, 16, 32 a cost model forecasts fastest for the rank count, image "
     "size and the bricks' screen rectangles, with the network of `compositing.latency_us` and "
     "`compositing.bandwidth_gbps`; every rank makes the same choice, and --stats says which and "
     "why: docs/compositing.md). Any rank count: ranks beyond the largest count the rounds can "
     "take first fold their image into a neighbour's.",
     Choice{member<&Scene::compositing, &CompositingSection::strategy>}},
    {"compositing.latency_us", "40",
     "`auto`: one message's latency between two ranks, microseconds (40: 10 Gbit/s Ethernet "
     "through one switch; about 2-5 for InfiniBand or a fat tree, 1 between ranks of one node).",
     Real{member<&Scene::compositing, &CompositingSection::latency_us>, {{"in [0, 1e6]", "must be {allowed} us"}}}},
    {"compositing.bandwidth_gbps", "10",
     "`auto`: one rank's link bandwidth, each way, Gbit/s (10 GbE; 100 for EDR InfiniBand).",
     Real{member<&Scene::compositing, &CompositingSection::bandwidth_gbps>, {{"in [0.001, 1e5]", "must be {allowed} Gbit/s"}}}},
    {"compositing.radix", "4",
     "k of `radix-k`: the most partners per round (2 is binary-swap; a round uses fewer "
     "where the rank count has no factor that large).",
     Int{member<&Scene::compositing, &CompositingSection::radix>, {{">= 2"}}}},
    {"compositing.precision", "float",
     "`float`: blend in float and round to 8 bits once per frame (swap strategies send partial "
     "composites at 16 bits), so every strategy and rank count gives the same frame within "
     "1/255; an `.exr` output then holds the unrounded frame. `rgba8`: the paper's 8-bit "
     "intermediate images (direct send rounds after every blend, swap strategies send 8-bit "
     "partials): fewer bytes, up to half a step of error per blend or round.",
     Choice{member<&Scene::compositing, &CompositingSection::precision>}},
    {"compositing.overlap", "true",
     "Direct send: each brick image is sent as soon as it is rendered, while the next brick "
     "renders, and rank 0 blends images as their visibility order allows. false: all images are "
     "sent after the last brick (to measure what overlap gains). The swap strategies need all "
     "of a rank's bricks first and ignore it.",
     Flag{member<&Scene::compositing, &CompositingSection::overlap>}},
    {"compositing.rle", "true",
     "Run-length code transparent runs in every image message (the paper's Fig. 7). false: every "
     "pixel travels (to measure what RLE saves).",
     Flag{member<&Scene::compositing, &CompositingSection::rle>}},
  };
}
