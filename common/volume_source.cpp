#include "common/volume_source.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace sortlast {

int sampleTypeBytes(SampleType t) {
  switch (t) {
    case SampleType::kUint8: return 1;
    case SampleType::kUint16:
    case SampleType::kInt16: return 2;
    case SampleType::kFloat32: return 4;
  }
  return 1;
}

bool VolumeDesc::isVtk() const {
  auto ext = std::filesystem::path(file).extension().string();
  return ext == ".vti" || ext == ".vtk";
}

namespace {

std::string dimsText(const glm::ivec3& d) {
  return "[" + std::to_string(d.x) + ", " + std::to_string(d.y) + ", " + std::to_string(d.z) + "]";
}

void checkFinite(float v, const glm::ivec3& ijk, const std::string& file) {
  if (!std::isfinite(v))
    throw InputError("volume.file " + file + ": " + (std::isnan(v) ? "NaN" : "infinite value") +
                     " at voxel " + dimsText(ijk));
}

float decode(const unsigned char* p, SampleType t, bool big_endian) {
  unsigned char b[4];
  int n = sampleTypeBytes(t);
  for (int i = 0; i < n; ++i) b[i] = big_endian ? p[n - 1 - i] : p[i];
  switch (t) {
    case SampleType::kUint8: return b[0];
    case SampleType::kUint16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
    case SampleType::kInt16: { int16_t v; std::memcpy(&v, b, 2); return v; }
    case SampleType::kFloat32: { float v; std::memcpy(&v, b, 4); return v; }
  }
  return 0.0f;
}

std::vector<float> readRawBox(const VolumeDesc& d, const IndexBox& box) {
  std::ifstream in(d.file, std::ios::binary);
  if (!in) throw InputError("volume.file " + d.file + ": cannot open");
  const glm::ivec3 n = d.grid.dims, s = box.size();
  const int bytes = sampleTypeBytes(d.type);
  std::vector<float> out(size_t(box.count()));
  std::vector<unsigned char> row(size_t(s.x) * bytes);
  size_t o = 0;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      long long first = box.lo.x + 1LL * n.x * (y + 1LL * n.y * z);
      in.seekg(d.header_bytes + first * bytes);
      in.read(reinterpret_cast<char*>(row.data()), std::streamsize(row.size()));
      if (!in) throw InputError("volume.file " + d.file + ": read failed at row y=" +
                                std::to_string(y) + " z=" + std::to_string(z) + " (truncated?)");
      for (int x = 0; x < s.x; ++x) {
        float v = decode(&row[size_t(x) * bytes], d.type, d.big_endian);
        if (d.type == SampleType::kFloat32) checkFinite(v, {box.lo.x + x, y, z}, d.file);
        out[o++] = v;
      }
    }
  return out;
}

std::vector<float> proceduralBox(const VolumeDesc& d, const IndexBox& box) {
  std::vector<float> out(size_t(box.count()));
  glm::dvec3 scale = 2.0 / glm::dvec3(glm::max(d.grid.dims - 1, glm::ivec3(1)));
  size_t o = 0;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y)
      for (int x = box.lo.x; x <= box.hi.x; ++x)
        out[o++] = float(proceduralValue(d.procedural, glm::dvec3(x, y, z) * scale - 1.0));
  return out;
}

}  // namespace

void validateVolume(VolumeDesc& d) {
  if (d.isProcedural()) {
    proceduralValue(d.procedural, glm::dvec3(0.0));  // rejects unknown names
  } else {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.file, ec))
      throw InputError("volume.file " + d.file + ": no such file");
    if (d.isVtk()) {
      readVtkGeometry(d);
    } else {
      auto size = (long long)std::filesystem::file_size(d.file, ec);
      long long need = d.header_bytes + d.grid.sampleCount() * sampleTypeBytes(d.type);
      if (size != need)
        throw InputError("volume.file " + d.file + ": file has " + std::to_string(size) +
                         " bytes, but volume.dims " + dimsText(d.grid.dims) + " of " +
                         std::to_string(sampleTypeBytes(d.type)) + "-byte samples" +
                         (d.header_bytes ? " after a header of " + std::to_string(d.header_bytes) + " bytes" : "") +
                         " need " + std::to_string(need));
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (d.grid.dims[a] < 2) throw InputError("volume.dims: every dimension must be >= 2, got " + dimsText(d.grid.dims));
    if (!(d.grid.spacing[a] > 0.0) || !std::isfinite(d.grid.spacing[a]))
      throw InputError("volume.spacing: every entry must be a finite number > 0");
  }
}

std::vector<float> readSamples(const VolumeDesc& d, const IndexBox& box) {
  if (d.isProcedural()) return proceduralBox(d, box);
  if (d.isVtk()) throw std::logic_error("readSamples: VTK volumes are read whole (readWholeVtk)");
  return readRawBox(d, box);
}

std::vector<float> extractBox(const std::vector<float>& whole, const glm::ivec3& n,
                              const IndexBox& box) {
  std::vector<float> out(size_t(box.count()));
  size_t o = 0;
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      const float* row = &whole[box.lo.x + size_t(n.x) * (y + size_t(n.y) * z)];
      for (int x = 0; x < box.size().x; ++x) out[o++] = row[x];
    }
  return out;
}

}  // namespace sortlast
