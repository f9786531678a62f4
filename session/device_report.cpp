#include "session/device_report.h"

#include <sched.h>

#include <algorithm>
#include <string>
#include <thread>

namespace sortlast {

NodePlace nodePlace(MPI_Comm comm) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  NodePlace p;
  MPI_Comm_rank(node, &p.rank);
  MPI_Comm_size(node, &p.size);
  MPI_Comm_free(&node);
  return p;
}

double ranksPerCore(MPI_Comm comm) {
  const NodePlace p = nodePlace(comm);
  int cores = 0;
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cores = CPU_COUNT(&set);
  if (cores < 1) cores = int(std::max(1u, std::thread::hardware_concurrency()));
  const double mine = double(p.size) / cores;
  double most = mine;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
  return most;
}

int ranksSharingDevice(const GlDeviceInfo& mine, MPI_Comm comm) {
  MPI_Comm node, same;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  // Software renderers each get a colour of their own: they share no device memory.
  int node_rank = 0;
  MPI_Comm_rank(node, &node_rank);
  const int colour = mine.device >= 0 ? mine.device : 1000 + node_rank;
  MPI_Comm_split(node, colour, 0, &same);
  int n = 1;
  MPI_Comm_size(same, &n);
  MPI_Comm_free(&same);
  MPI_Comm_free(&node);
  return n;
}

nlohmann::json deviceJson(const GlDeviceInfo& i, int rank) {
  nlohmann::json j{{"rank", rank},           {"host", i.host},         {"backend", i.backend},
                   {"device", i.device},     {"devices", i.devices},   {"vendor", i.vendor},
                   {"renderer", i.renderer}, {"version", i.version}};
  if (i.gpu_free_mib >= 0) {
    j["gpu_memory_mib"] = {{"free", i.gpu_free_mib},
                           {"total", i.gpu_total_mib >= 0 ? nlohmann::json(i.gpu_total_mib) : nlohmann::json()},
                           {"source", i.gpu_memory_source}};
  } else {
    j["gpu_memory_mib"] = nullptr;
  }
  return j;
}

nlohmann::json deviceJson(const std::vector<GlDeviceInfo>& all) {
  nlohmann::json a = nlohmann::json::array();
  for (size_t r = 0; r < all.size(); ++r) a.push_back(deviceJson(all[r], int(r)));
  return a;
}

std::vector<GlDeviceInfo> gatherDeviceInfo(const GlDeviceInfo& mine, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // As JSON text: variable-length strings in one Gatherv.
  const std::string text = deviceJson(mine, rank).dump();
  int length = int(text.size());
  std::vector<int> lengths(rank == 0 ? size_t(size) : 0), offsets(lengths.size());
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, comm);
  std::string all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) offsets[size_t(r)] = total, total += lengths[size_t(r)];
    all.resize(size_t(total));
  }
  MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, comm);
  std::vector<GlDeviceInfo> out;
  for (int r = 0; rank == 0 && r < size; ++r) {
    const auto j = nlohmann::json::parse(all.substr(size_t(offsets[size_t(r)]), size_t(lengths[size_t(r)])));
    GlDeviceInfo i;
    i.host = j.at("host");
    i.backend = j.at("backend");
    i.device = j.at("device");
    i.devices = j.at("devices");
    i.vendor = j.at("vendor");
    i.renderer = j.at("renderer");
    i.version = j.at("version");
    if (!j.at("gpu_memory_mib").is_null()) {
      const auto& m = j.at("gpu_memory_mib");
      i.gpu_free_mib = m.at("free");
      i.gpu_total_mib = m.at("total").is_null() ? -1.0 : double(m.at("total"));
      i.gpu_memory_source = m.at("source");
    }
    out.push_back(std::move(i));
  }
  return out;
}

}  // namespace sortlast
