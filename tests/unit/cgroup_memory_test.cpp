// The cgroup memory limit (session/cgroup_memory.h) on fake cgroup trees: v2, v1, a hybrid
// system, nested limits, "max", a container's mount root, and mountinfo's fields.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "session/cgroup_memory.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

class CgroupMemory : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    root_ = fs::temp_directory_path() / ("sortlast_cgroup_test_" + std::to_string(::getpid()) + "_" +
                                         std::to_string(counter++));
    fs::create_directories(root_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  void write(const fs::path& rel, const std::string& text) {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << text;
  }
  CgroupMounts mounts() const {
    CgroupMounts m;
    m.v2 = (root_ / "unified").string();
    m.v1_memory = (root_ / "memory").string();
    return m;
  }
  fs::path root_;
};

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

TEST_F(CgroupMemory, V2TightestAlongThePath) {
  // Slurm: the job's cgroup holds the limit, the step's below it says "max".
  write("unified/memory.max", "max\n");  // the root has none; a stray file must not count as one
  write("unified/slurm/job_7/memory.max", "2147483648\n");
  write("unified/slurm/job_7/step_0/memory.max", "max\n");
  auto l = cgroupMemoryLimit("0::/slurm/job_7/step_0\n", mounts());
  ASSERT_TRUE(l);
  EXPECT_EQ(l->bytes, 2 * kGiB);
  EXPECT_EQ(l->file, (root_ / "unified/slurm/job_7/memory.max").string());
  // A tighter limit below wins.
  write("unified/slurm/job_7/step_0/memory.max", "1073741824\n");
  EXPECT_EQ(cgroupMemoryLimit("0::/slurm/job_7/step_0\n", mounts())->bytes, 1 * kGiB);
}

TEST_F(CgroupMemory, NoLimit) {
  write("unified/a/memory.max", "max\n");
  EXPECT_FALSE(cgroupMemoryLimit("0::/a\n", mounts()));
  // v1's "no limit" is the largest page-aligned long.
  write("memory/a/memory.limit_in_bytes", "9223372036854771712\n");
  EXPECT_FALSE(cgroupMemoryLimit("4:memory:/a\n0::/\n", mounts()));
  // Nothing mounted, nothing read.
  EXPECT_FALSE(cgroupMemoryLimit("0::/a\n", CgroupMounts{}));
}

TEST_F(CgroupMemory, V1WhereV2HasNoMemoryController) {
  // A hybrid system (this test machine's kind): the unified hierarchy has no memory.max files,
  // the memory controller lives on v1.
  write("unified/cgroup.procs", "");
  write("memory/docker/abc/memory.limit_in_bytes", "3221225472\n");
  const std::string self = "9:name=systemd:/\n4:memory:/docker/abc\n1:cpu,cpuacct:/\n0::/\n";
  auto l = cgroupMemoryLimit(self, mounts());
  ASSERT_TRUE(l);
  EXPECT_EQ(l->bytes, 3 * kGiB);
  // A container that mounts its own cgroup (mountinfo's root /docker/abc) at the mount point.
  CgroupMounts m = mounts();
  m.v1_memory = (root_ / "memory/docker/abc").string();
  m.v1_memory_root = "/docker/abc";
  EXPECT_EQ(cgroupMemoryLimit(self, m)->bytes, 3 * kGiB);
}

TEST_F(CgroupMemory, PathOutsideTheMountReadsTheMountOnly) {
  write("unified/memory.max", "1073741824\n");
  write("x/memory.max", "1\n");  // beside the mount: must not be read
  EXPECT_EQ(cgroupMemoryLimit("0::/../x\n", mounts())->bytes, 1 * kGiB);
}

TEST(CgroupMounts, FromMountinfo) {
  const std::string info =
      "30 22 0:27 / /sys/fs/cgroup rw,relatime - tmpfs tmpfs rw,mode=755\n"
      "31 30 0:28 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu\n"
      "34 30 0:31 /docker/abc /sys/fs/cgroup/memory rw,relatime shared:9 - cgroup cgroup rw,memory\n"
      "40 30 0:37 / /sys/fs/cgroup/unified rw,relatime - cgroup2 cgroup2 rw\n";
  CgroupMounts m = cgroupMounts(info);
  EXPECT_EQ(m.v2, "/sys/fs/cgroup/unified");
  EXPECT_EQ(m.v2_root, "/");
  EXPECT_EQ(m.v1_memory, "/sys/fs/cgroup/memory");
  EXPECT_EQ(m.v1_memory_root, "/docker/abc");
  EXPECT_TRUE(cgroupMounts("garbage\n\n1 2 3\n").v2.empty());
}

}  // namespace
}  // namespace sortlast
