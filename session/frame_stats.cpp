#include "session/frame_stats.h"

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>

namespace sortlast {

static_assert(sizeof(RankFrameStats) % sizeof(double) == 0, "RankFrameStats must be all doubles");

std::vector<RankFrameStats> gatherStats(const RankFrameStats& mine, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = sizeof(RankFrameStats) / sizeof(double);
  std::vector<RankFrameStats> all(rank == 0 ? size_t(size) : 0);
  MPI_Gather(&mine, n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, 0, comm);
  return all;
}

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux reports KiB
}

double currentRssMiB() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0.0;
  char line[256];
  long long kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmRSS: %lld kB", &kib) == 1) break;
  std::fclose(f);
  return kib / 1024.0;
}

double heapInUseMiB() {
  const struct mallinfo2 m = mallinfo2();
  return double(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

nlohmann::json stagesJson(const std::vector<RankFrameStats>& ranks, double total_s) {
  struct Stage {
    const char* name;
    double RankFrameStats::*seconds;
  };
  // render_s is the CPU's time in the draw calls ("issue"); on llvmpipe it holds the drawing itself.
  const Stage stages[] = {{"draw", &RankFrameStats::draw_s},         {"issue", &RankFrameStats::render_s},
                          {"readback", &RankFrameStats::readback_s}, {"encode", &RankFrameStats::encode_s},
                          {"exchange", &RankFrameStats::exchange_s}, {"composite", &RankFrameStats::composite_s}};
  nlohmann::json j;
  for (const Stage& st : stages) {
    nlohmann::json a = nlohmann::json::array();
    for (const RankFrameStats& r : ranks) a.push_back(r.*st.seconds);
    j[std::string(st.name) + "_s"] = a;
  }
  j["wall_s"] = nlohmann::json::array();
  for (const RankFrameStats& r : ranks) j["wall_s"].push_back(r.wall_s);
  if (ranks.empty()) return j;
  double draw = 0;
  size_t slowest = 0;
  for (size_t i = 0; i < ranks.size(); ++i) {
    draw = std::max(draw, ranks[i].draw_s);
    if (ranks[i].wall_s > ranks[slowest].wall_s) slowest = i;
  }
  const RankFrameStats& r = ranks[slowest];
  const Stage* critical = &stages[0];
  double busy = 0;
  for (const Stage& st : stages) {
    if (r.*st.seconds > r.*critical->seconds) critical = &st;
    // The GPU's draw runs beside the CPU's issue of it: counted once, as the larger.
    if (st.seconds != &RankFrameStats::render_s) busy += r.*st.seconds;
  }
  busy += std::max(0.0, r.render_s - r.draw_s);
  j["frame_draw_s"] = draw;
  j["outside_draw_s"] = std::max(0.0, total_s - draw);
  j["outside_draw_share"] = total_s > 0 ? std::max(0.0, total_s - draw) / total_s : 0.0;
  j["critical"] = critical->name;
  j["slowest_rank"] = int(slowest);
  j["overlap_s"] = std::max(0.0, busy - r.wall_s);
  return j;
}

nlohmann::json frameJson(int frame, const std::vector<RankFrameStats>& ranks, double composite_s,
                         double total_s) {
  nlohmann::json j;
  j["frame"] = frame;
  double raw = 0, rle = 0;
  for (const char* key : {"render_s", "encode_s", "transfer_s", "peak_rss_mb", "rss_mb", "heap_mb", "bricks_rendered",
                          "bricks_skipped", "particles_held", "particle_rounds", "bytes_sent"})
    j[key] = nlohmann::json::array();
  for (const RankFrameStats& r : ranks) {
    j["render_s"].push_back(r.render_s);
    j["encode_s"].push_back(r.encode_s);
    j["transfer_s"].push_back(r.transfer_s);
    j["peak_rss_mb"].push_back(r.peak_rss_mb);
    j["rss_mb"].push_back(r.rss_mb);
    j["heap_mb"].push_back(r.heap_mb);
    j["bricks_rendered"].push_back(int(r.bricks_rendered));
    j["bricks_skipped"].push_back(int(r.bricks_skipped));
    j["particles_held"].push_back((long long)r.particles_held);
    j["particle_rounds"].push_back(int(r.particle_rounds));
    j["bytes_sent"].push_back((long long)r.bytes_sent);
    raw += r.bytes_raw;
    rle += r.bytes_rle;
  }
  j["bytes_raw"] = raw;
  j["bytes_rle"] = rle;
  j["rle_ratio"] = raw > 0 ? rle / raw : 1.0;  // encoded size as a fraction of the raw size
  j["composite_s"] = composite_s;
  j["total_s"] = total_s;
  return j;
}

}  // namespace sortlast
