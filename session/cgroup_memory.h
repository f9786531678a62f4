#pragma once
// The memory limit of this process's control group: what a batch scheduler (Slurm's cgroup
// plugin, a container runtime) allows the job on this node, which may be far below the node's
// free memory. A job past it is killed by the kernel's OOM killer, without our message; the
// memory budget (memory_budget.h) takes it into account so that such a scene is refused instead.
#include <optional>
#include <string>

namespace sortlast {

// Where the cgroup file systems are mounted (fields of /proc/self/mountinfo): the unified (v2)
// hierarchy and v1's memory controller, each with the cgroup path its mount shows as its root
// ("/" unless a container mounts its own cgroup there). Empty mount: not mounted.
struct CgroupMounts {
  std::string v2, v2_root = "/";
  std::string v1_memory, v1_memory_root = "/";
};
CgroupMounts cgroupMounts(const std::string& mountinfo);

struct CgroupLimit {
  double bytes = 0;
  std::string file;  // the limit file that set it (the tightest along the path)
};

// The tightest limit on this process's cgroup and its ancestors: v2's memory.max ("max": none),
// or where no v2 limit applies, v1's memory.limit_in_bytes (values of 2^62 or more: none).
// `proc_self_cgroup` is /proc/self/cgroup's text ("0::/PATH" for v2, "N:memory:/PATH" for v1).
// A limit above the whole hierarchy's mount point is not seen (the kernel hides it from a
// container too). nullopt: no limit set.
std::optional<CgroupLimit> cgroupMemoryLimit(const std::string& proc_self_cgroup,
                                             const CgroupMounts& mounts);

// This process's limit, from /proc/self/cgroup and /proc/self/mountinfo. The environment variable
// SORTLAST_CGROUP_ROOT=DIR stands in for the mounts (v2 at DIR, v1's memory at DIR/memory), so the
// tests can put a limit in front of a job without root.
std::optional<CgroupLimit> processCgroupMemoryLimit();

}  // namespace sortlast
