#include "io/volume_source.h"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"
#include "io/nrrd_header.h"

namespace sortlast {

VolumeFormat VolumeDesc::formatOf() const {
  const std::string ext = std::filesystem::path(file).extension().string();
  if (format == "raw") return VolumeFormat::kRaw;
  if (format == "hdf5" || (format == "auto" && (ext == ".h5" || ext == ".hdf5"))) return VolumeFormat::kHdf5;
  if (format == "netcdf" || (format == "auto" && ext == ".nc")) return VolumeFormat::kNetcdf;
  if (format == "nrrd" || (format == "auto" && (ext == ".nrrd" || ext == ".nhdr"))) return VolumeFormat::kNrrd;
  if (format == "vtk" || (format == "auto" && (ext == ".vti" || ext == ".vtk")))
    return ext == ".vtk" ? VolumeFormat::kLegacyVtk : VolumeFormat::kVti;
  return VolumeFormat::kRaw;
}

bool VolumeDesc::isVtk() const {
  const VolumeFormat f = formatOf();
  return f == VolumeFormat::kVti || f == VolumeFormat::kLegacyVtk;
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
  unsigned char b[8];
  int n = sampleTypeBytes(t);
  for (int i = 0; i < n; ++i) b[i] = big_endian ? p[n - 1 - i] : p[i];
  switch (t) {
    case SampleType::kUint8: return b[0];
    case SampleType::kUint16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
    case SampleType::kInt16: { int16_t v; std::memcpy(&v, b, 2); return v; }
    case SampleType::kFloat32: { float v; std::memcpy(&v, b, 4); return v; }
    case SampleType::kFloat64: { double v; std::memcpy(&v, b, 8); return float(v); }
  }
  return 0.0f;
}

bool isFloat(SampleType t) { return t == SampleType::kFloat32 || t == SampleType::kFloat64; }

// One row of the file's samples (x from x0, at y, z) into `out`, checking float ones are finite.
void decodeRow(const VolumeDesc& d, const std::vector<unsigned char>& row, int x0, int y, int z,
               float*& out) {
  const int bytes = sampleTypeBytes(d.type);
  const int count = int(row.size()) / bytes;
  for (int x = 0; x < count; ++x) {
    const float v = decode(&row[size_t(x) * bytes], d.type, d.big_endian);
    if (isFloat(d.type)) checkFinite(v, {x0 + x, y, z}, d.file);
    *out++ = v;
  }
}

// The file the samples are in: a NRRD header's data file, else volume.file.
const std::string& dataPath(const VolumeDesc& d) { return d.data_file.empty() ? d.file : d.data_file; }

std::vector<float> readRawBox(const VolumeDesc& d, const IndexBox& box) {
  std::ifstream in(dataPath(d), std::ios::binary);
  if (!in) throw InputError("volume.file " + d.file + ": cannot open " + dataPath(d));
  const glm::ivec3 n = d.grid.dims, s = box.size();
  const int bytes = sampleTypeBytes(d.type);
  std::vector<float> out(size_t(box.count()));
  std::vector<unsigned char> row(size_t(s.x) * bytes);
  float* o = out.data();
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      long long first = box.lo.x + 1LL * n.x * (y + 1LL * n.y * z);
      in.seekg(d.header_bytes + first * bytes);
      in.read(reinterpret_cast<char*>(row.data()), std::streamsize(row.size()));
      if (!in) throw InputError("volume.file " + d.file + ": read failed at row y=" +
                                std::to_string(y) + " z=" + std::to_string(z) + " (truncated?)");
      decodeRow(d, row, box.lo.x, y, z, o);
    }
  return out;
}

// NRRD gzip: one stream from the start of the compressed data, skipping (decompressing and
// dropping) what lies before each row of the box: a box costs the decompression of the file up
// to its last row, so a rank's bricks each decompress the front of the file again.
std::vector<float> readGzipBox(const VolumeDesc& d, const IndexBox& box) {
  const std::string& path = dataPath(d);
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw InputError("volume.file " + d.file + ": cannot open " + path);
  if (::lseek(fd, off_t(d.header_bytes), SEEK_SET) < 0) {
    ::close(fd);
    throw InputError("volume.file " + d.file + ": cannot seek to the gzip data");
  }
  gzFile gz = gzdopen(fd, "rb");
  if (!gz) {
    ::close(fd);
    throw InputError("volume.file " + d.file + ": cannot read the gzip data");
  }
  struct Closer { gzFile g; ~Closer() { gzclose(g); } } closer{gz};
  gzbuffer(gz, 1 << 18);
  const glm::ivec3 n = d.grid.dims, s = box.size();
  const int bytes = sampleTypeBytes(d.type);
  std::vector<float> out(size_t(box.count()));
  std::vector<unsigned char> row(size_t(s.x) * bytes);
  float* o = out.data();
  for (int z = box.lo.z; z <= box.hi.z; ++z)
    for (int y = box.lo.y; y <= box.hi.y; ++y) {
      const long long first = (box.lo.x + 1LL * n.x * (y + 1LL * n.y * z)) * bytes;
      if (gzseek(gz, z_off_t(d.gzip_skip + first), SEEK_SET) < 0 ||
          gzread(gz, row.data(), unsigned(row.size())) != int(row.size())) {
        int err = 0;
        const char* msg = gzerror(gz, &err);
        throw InputError("volume.file " + d.file + ": gzip data ends or is corrupt before row y=" +
                         std::to_string(y) + " z=" + std::to_string(z) +
                         (err != Z_OK && err != Z_STREAM_END && msg ? std::string(" (") + msg + ")" : std::string(" (truncated?)")));
      }
      decodeRow(d, row, box.lo.x, y, z, o);
    }
  return out;
}

// Bytes from the start of `path` past `lines` text lines (a NRRD line skip).
long long skipLines(const std::string& path, long long start, int lines, const std::string& file) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(start);
  std::string line;
  long long at = start;
  for (int i = 0; i < lines; ++i) {
    if (!std::getline(in, line)) throw InputError("volume.file " + file + ": NRRD 'line skip' " + std::to_string(lines) + " runs past the end of " + path);
    at += (long long)line.size() + 1;
  }
  return at;
}

// A NRRD header's layout into the description: dims, spacing, type, where the samples are.
void describeNrrd(VolumeDesc& d) {
  const NrrdHeader h = readNrrdHeader(d.file);
  d.grid.dims = h.sizes;
  d.grid.spacing = h.spacing;
  d.type = h.type;
  d.big_endian = h.big_endian;
  d.gzip = h.gzip;
  d.data_file = h.data_file.empty() ? d.file : (std::filesystem::path(d.file).parent_path() / h.data_file).string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(d.data_file, ec))
    throw InputError("volume.file " + d.file + ": NRRD field 'data file': no such file " + d.data_file);
  const long long start = skipLines(d.data_file, h.data_file.empty() ? h.header_bytes : 0, h.line_skip, d.file);
  const long long size = (long long)std::filesystem::file_size(d.data_file, ec);
  const long long need = d.grid.sampleCount() * sampleTypeBytes(d.type);
  if (h.gzip) {
    d.header_bytes = start;
    d.gzip_skip = h.byte_skip;
    return;  // the stream's length is known only by reading it: a short one fails at its row
  }
  d.header_bytes = h.byte_skip == -1 ? size - need : start + h.byte_skip;
  if (d.header_bytes < 0 || size - d.header_bytes < need)
    throw InputError("volume.file " + d.file + ": NRRD data in " + d.data_file + " has " +
                     std::to_string(std::max(0LL, size - std::max(0LL, d.header_bytes))) + " bytes after the header and skips, but sizes " +
                     dimsText(d.grid.dims) + " of " + std::to_string(sampleTypeBytes(d.type)) +
                     "-byte samples need " + std::to_string(need) + " (truncated?)");
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

void requireVolumeFormatBuilt(const VolumeDesc& d) {
  if (d.isProcedural()) return;
  const std::string what = "volume.file " + d.file;
  switch (d.formatOf()) {
    case VolumeFormat::kVti:
    case VolumeFormat::kLegacyVtk:
      if (!build::kVtk) refuseMissingFeature(Feature::kVtk, what);
      break;
    case VolumeFormat::kHdf5:
      if (!build::kHdf5) refuseMissingFeature(Feature::kHdf5, what);
      break;
    case VolumeFormat::kNetcdf:
      if (!build::kNetcdf) refuseMissingFeature(Feature::kNetcdf, what);
      break;
    case VolumeFormat::kRaw:
    case VolumeFormat::kNrrd: break;
  }
}

void validateVolume(VolumeDesc& d) {
  requireVolumeFormatBuilt(d);
  if (d.isProcedural()) {
    proceduralValue(d.procedural, glm::dvec3(0.0));  // rejects unknown names
  } else {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.file, ec))
      throw InputError("volume.file " + d.file + ": no such file");
    const VolumeFormat format = d.formatOf();
    // Each `if constexpr`: a format's reader is compiled only where the build has its library
    // (requireVolumeFormatBuilt has refused the others).
    if (format == VolumeFormat::kVti || format == VolumeFormat::kLegacyVtk) {
      if constexpr (build::kVtk) readVtkGeometry(d);
    } else if (format == VolumeFormat::kNrrd) {
      describeNrrd(d);
    } else if (format == VolumeFormat::kHdf5) {
      if constexpr (build::kHdf5) describeHdf5(d);
    } else if (format == VolumeFormat::kNetcdf) {
      if constexpr (build::kNetcdf) describeNetcdf(d);
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
  requireVolumeFormatBuilt(d);
  switch (d.formatOf()) {
    case VolumeFormat::kLegacyVtk:
      throw std::logic_error("readSamples: legacy VTK volumes are read whole (readWholeVtk)");
    case VolumeFormat::kVti:
      if constexpr (build::kVtk) return readVtiBox(d, box);
      break;
    case VolumeFormat::kNrrd: return d.gzip ? readGzipBox(d, box) : readRawBox(d, box);
    case VolumeFormat::kRaw: return readRawBox(d, box);
    case VolumeFormat::kHdf5:
      if constexpr (build::kHdf5) return readHdf5Box(d, box);
      break;
    case VolumeFormat::kNetcdf:
      if constexpr (build::kNetcdf) return readNetcdfBox(d, box);
      break;
  }
  return {};
}

std::string allSamplesMissing(const std::string& file) {
  return "volume.file " + file +
         ": every sample is missing (equal to the variable's _FillValue or missing_value): "
         "nothing to draw";
}

std::pair<float, float> presentRange(const std::vector<float>& samples, const std::string& file) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  widenRange(samples.data(), samples.size(), lo, hi);
  if (!(lo <= hi)) throw InputError(allSamplesMissing(file));
  return {lo, hi};
}

std::vector<float> readWholeVolume(const VolumeDesc& d) {
  if (d.readsWhole()) {
    requireVolumeFormatBuilt(d);
    if constexpr (build::kVtk) return readWholeVtk(d);
  }
  return readSamples(d, {{0, 0, 0}, d.grid.dims - 1});
}

namespace {

template <class T>
void unpackAs(const T* in, bool xyz, const IndexBox& box, float* out, const std::string& where,
              const std::vector<std::pair<std::string, double>>& fills) {
  const glm::ivec3 s = box.size();
  size_t o = 0;
  for (int z = 0; z < s.z; ++z)
    for (int y = 0; y < s.y; ++y)
      for (int x = 0; x < s.x; ++x) {
        const size_t i = xyz ? (size_t(x) * s.y + y) * s.z + z : (size_t(z) * s.y + y) * s.x + x;
        const T v = in[i];
        // A missing sample (NetCDF's _FillValue, missing_value) becomes NaN, which every renderer
        // and the reference draw as transparent (docs/data_hdf5_netcdf.md "Missing values").
        if (std::any_of(fills.begin(), fills.end(), [&](const auto& f) { return double(v) == f.second; })) {
          out[o++] = std::numeric_limits<float>::quiet_NaN();
          continue;
        }
        const float f = float(v);
        if (!std::isfinite(f))
          throw InputError(where + ": " + (std::isnan(f) ? "NaN" : "infinite value") + " at voxel " +
                           dimsText(box.lo + glm::ivec3(x, y, z)));
        out[o++] = f;
      }
}

}  // namespace

void unpackBox(const void* in, SampleType type, bool xyz, const IndexBox& box, float* out,
               const std::string& where, const std::vector<std::pair<std::string, double>>& fills) {
  switch (type) {
    case SampleType::kUint8: return unpackAs(static_cast<const uint8_t*>(in), xyz, box, out, where, fills);
    case SampleType::kUint16: return unpackAs(static_cast<const uint16_t*>(in), xyz, box, out, where, fills);
    case SampleType::kInt16: return unpackAs(static_cast<const int16_t*>(in), xyz, box, out, where, fills);
    case SampleType::kFloat32: return unpackAs(static_cast<const float*>(in), xyz, box, out, where, fills);
    case SampleType::kFloat64: return unpackAs(static_cast<const double*>(in), xyz, box, out, where, fills);
  }
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
