// unpackBox (io/volume_source.h): the HDF5 and NetCDF readers' arrays in C order, zyx or xyz,
// into a box's samples x fastest; NaN refused by voxel, fill values made NaN. And formatOf's extensions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "io/volume_source.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {

namespace {
// The value a test volume holds at grid voxel (x, y, z).
int valueAt(int x, int y, int z) { return x + 10 * y + 100 * z; }
}  // namespace

TEST(VolumeUnpack, ZyxAndXyzGiveTheSameBox) {
  const IndexBox box{{1, 2, 3}, {4, 4, 5}};  // 4 x 3 x 3 samples
  const glm::ivec3 s = box.size();
  std::vector<int16_t> zyx, xyz;
  for (int z = 0; z < s.z; ++z)
    for (int y = 0; y < s.y; ++y)
      for (int x = 0; x < s.x; ++x) zyx.push_back(int16_t(valueAt(box.lo.x + x, box.lo.y + y, box.lo.z + z)));
  for (int x = 0; x < s.x; ++x)
    for (int y = 0; y < s.y; ++y)
      for (int z = 0; z < s.z; ++z) xyz.push_back(int16_t(valueAt(box.lo.x + x, box.lo.y + y, box.lo.z + z)));
  std::vector<float> a(zyx.size()), b(xyz.size());
  unpackBox(zyx.data(), SampleType::kInt16, false, box, a.data(), "w");
  unpackBox(xyz.data(), SampleType::kInt16, true, box, b.data(), "w");
  EXPECT_EQ(a, b);
  size_t i = 0;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y)
      for (int x = box.lo.x; x <= box.hi.x; ++x) EXPECT_EQ(a[i++], float(valueAt(x, y, z)));
}

TEST(VolumeUnpack, Float32InPlace) {
  const IndexBox box{{0, 0, 0}, {2, 1, 1}};
  std::vector<float> v = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const std::vector<float> expected = v;
  unpackBox(v.data(), SampleType::kFloat32, false, box, v.data(), "w");
  EXPECT_EQ(v, expected);
}

TEST(VolumeUnpack, RefusesNanAndInfinityByVoxel) {
  const IndexBox box{{10, 20, 30}, {11, 21, 31}};
  std::vector<double> v(8, 1.0);
  v[1 + 2 * (1 + 2 * 1)] = std::nan("");  // (x, y, z) = (1, 1, 1) in the box
  std::vector<float> out(8);
  EXPECT_EQ(inputErrorOf([&] { unpackBox(v.data(), SampleType::kFloat64, false, box, out.data(), "volume.file f.h5: dataset /v"); }),
            "volume.file f.h5: dataset /v: NaN at voxel [11, 21, 31]");
  v.assign(8, 1.0);
  v[1] = 1e300;  // beyond float: infinite once converted, as the raw reader finds it
  EXPECT_EQ(inputErrorOf([&] { unpackBox(v.data(), SampleType::kFloat64, false, box, out.data(), "w"); }),
            "w: infinite value at voxel [11, 20, 30]");
}

// A fill value marks a missing sample: it becomes NaN (drawn transparent), the others unchanged;
// a NaN stored in the data itself is still refused.
TEST(VolumeUnpack, FillValuesBecomeNan) {
  const IndexBox box{{10, 20, 30}, {11, 21, 31}};
  std::vector<uint8_t> u(8, 3);
  u[2] = 255;  // (0, 1, 0)
  u[5] = 7;
  std::vector<float> out(8);
  unpackBox(u.data(), SampleType::kUint8, false, box, out.data(), "volume.file f.nc: variable t",
            {{"_FillValue", 255.0}, {"missing_value", 7.0}});
  for (int i = 0; i < 8; ++i) {
    if (i == 2 || i == 5)
      EXPECT_TRUE(std::isnan(out[i])) << i;
    else
      EXPECT_EQ(out[i], 3.0f) << i;
  }
}

TEST(VolumeUnpack, FormatsByExtension) {
  VolumeDesc d;
  for (const char* f : {"a.h5", "a.hdf5"}) {
    d.file = f;
    EXPECT_EQ(d.formatOf(), VolumeFormat::kHdf5) << f;
  }
  d.file = "a.nc";
  EXPECT_EQ(d.formatOf(), VolumeFormat::kNetcdf);
  d.file = "a.dat";
  d.format = "hdf5";
  EXPECT_EQ(d.formatOf(), VolumeFormat::kHdf5);
  d.format = "netcdf";
  EXPECT_EQ(d.formatOf(), VolumeFormat::kNetcdf);
  EXPECT_FALSE(d.readsWhole());
}

}  // namespace sortlast
