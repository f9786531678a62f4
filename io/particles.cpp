// Loading particle centres: format choice, the raw and CSV readers, and the checks every format
// shares (count, finite positions). VTK files are read in vtk_particles.cpp, procedural sets are
// made in procedural_particles.cpp.
#include "io/particles.h"
#include "io/particle_readers.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "common/build_features.h"
#include "common/error.h"
#include "common/missing_feature.h"

namespace sortlast {

namespace {

constexpr long long kDefaultProceduralCount = 4096;

std::string formatByName(const ParticleDesc& d) {
  if (d.format != "auto") {
    if (d.format != "vtk" && d.format != "raw" && d.format != "csv" && d.format != "hdf5")
      throw InputError("particles.format: unknown format '" + d.format +
                       "' (known: auto, vtk, raw, csv, hdf5)");
    return d.format;
  }
  std::string ext = std::filesystem::path(d.file).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".vtk" || ext == ".vtp" || ext == ".vtu") return "vtk";
  if (ext == ".csv") return "csv";
  if (ext == ".h5" || ext == ".hdf5") return "hdf5";
  return "raw";
}

// The format, refused with the CMake option that builds it where this build has no reader for it.
std::string formatOf(const ParticleDesc& d) {
  const std::string format = formatByName(d);
  if (format == "vtk" && !build::kVtk) refuseMissingFeature(Feature::kVtk, "particles.file " + d.file);
  if (format == "hdf5" && !build::kHdf5) refuseMissingFeature(Feature::kHdf5, "particles.file " + d.file);
  return format;
}

// A raw file holds little-endian float32 x,y,z triples, no header: its size must be a multiple of
// 12 and, when particles.count is given, 12 x count. Checked before reading the file.
void checkRawSize(long long size, const std::string& file, long long declared,
                  const std::string& hint) {
  if (size % 12 != 0)
    throw InputError("particles.file " + file + ": raw file has " + std::to_string(size) +
                     " bytes, not a multiple of 12 (x, y, z as float32)" + hint);
  if (declared >= 0 && size != declared * 12)
    throw InputError("particles.file " + file + ": raw file has " + std::to_string(size) +
                     " bytes = " + std::to_string(size / 12) +
                     " particles, but particles.count is " + std::to_string(declared) + " (" +
                     std::to_string(declared * 12) + " bytes)");
}

std::string readWholeFile(const std::string& file, std::ios::openmode mode) {
  std::ifstream in(file, mode);
  if (!in) throw InputError("particles.file " + file + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("particles.file " + file + ": read failed");
  return text.str();
}

std::string trim(std::string_view s) {
  size_t b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string_view::npos ? "" : std::string(s.substr(b, e - b + 1));
}

bool parseNumber(const std::string& field, double& v) {
  const char* first = field.data();
  const char* last = first + field.size();
  if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
  auto [p, ec] = std::from_chars(first, last, v);
  return ec == std::errc() && p == last && first != last;
}

// x,y,z per line; extra columns ignored; `#` starts a comment; blank lines skipped; the first
// data line may be a header (its first field is not a number).
std::vector<glm::vec3> readCsv(std::string_view all, const std::string& file) {
  std::vector<glm::vec3> out;
  bool first_data_line = true;
  long long n = 0;
  for (size_t pos = 0; pos < all.size();) {
    ++n;
    size_t end = all.find('\n', pos);
    if (end == std::string_view::npos) end = all.size();
    std::string_view line = all.substr(pos, end - pos);
    pos = end + 1;
    std::string text = trim(line.substr(0, line.find('#')));
    if (text.empty()) continue;
    std::vector<std::string> fields;
    for (size_t start = 0;;) {
      size_t comma = text.find(',', start);
      fields.push_back(trim(std::string_view(text).substr(start, comma - start)));
      if (comma == std::string::npos || fields.size() == 3) break;
      start = comma + 1;
    }
    double xyz[3];
    bool ok = fields.size() == 3;
    for (int a = 0; ok && a < 3; ++a) ok = parseNumber(fields[size_t(a)], xyz[a]);
    double ignored;
    if (!ok && first_data_line && !parseNumber(fields[0], ignored)) {
      first_data_line = false;  // a header such as "x,y,z"
      continue;
    }
    first_data_line = false;
    if (!ok)
      throw InputError("particles.file " + file + " line " + std::to_string(n) +
                       ": expected x,y,z numbers, got '" + text + "'");
    // Checked in double: converting a double beyond float's range to float is undefined.
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    bool fits = true;
    for (double v : xyz) fits = fits && std::isfinite(v) && std::abs(v) <= kFloatMax;
    if (!fits)
      throw InputError("particles.file " + file + " line " + std::to_string(n) +
                       ": NaN or infinite (as float32) position at particle " +
                       std::to_string(out.size()));
    out.push_back({float(xyz[0]), float(xyz[1]), float(xyz[2])});
  }
  return out;
}

// `first`: the index in the file of ps[0] (a rank's share), so messages name the file's index.
void checkFinite(const std::vector<glm::vec3>& ps, const std::string& file, long long first = 0) {
  for (size_t i = 0; i < ps.size(); ++i) {
    const glm::vec3& p = ps[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(
          "particles.file " + file + ": " +
          (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z) ? "NaN" : "infinite") +
          " position at particle " + std::to_string(first + (long long)i));
  }
}

// The GPU computes in float, squaring distances: a coordinate beyond kMaxCoordinate would
// overflow float (3.4e38) there. Procedural sets too (particles.spacing scales them).
void checkMagnitude(const std::vector<glm::vec3>& ps, const std::string& what, long long first = 0) {
  for (size_t i = 0; i < ps.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (std::abs(double(ps[i][a])) > kMaxCoordinate) {
        char value[32];
        std::snprintf(value, sizeof value, "%g", double(ps[i][a]));
        throw InputError(
            what + ": particle " + std::to_string(first + (long long)i) + " has coordinate " + value +
            ", beyond +-1e18 (float math on the GPU squares distances and would overflow)");
      }
}

// What every format's positions must satisfy.
void checkLoaded(const std::vector<glm::vec3>& ps, const std::string& file, long long declared) {
  if (declared >= 0 && static_cast<long long>(ps.size()) != declared)
    throw InputError("particles.file " + file + ": holds " + std::to_string(ps.size()) +
                     (ps.size() == 1 ? " particle" : " particles") +
                     ", but particles.count is " + std::to_string(declared));
  checkFinite(ps, file);
  checkMagnitude(ps, "particles.file " + file);
}

}  // namespace

Box3 ParticleSet::bounds() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{glm::dvec3(inf), glm::dvec3(-inf)};
  for (const glm::vec3& p : positions) {
    b.lo = glm::min(b.lo, glm::dvec3(p));
    b.hi = glm::max(b.hi, glm::dvec3(p));
  }
  return b;
}

bool readsInShares(const ParticleDesc& d) { return !d.file.empty() && formatOf(d) == "hdf5"; }

ParticleSet loadParticleShare(const ParticleDesc& d, int part, int parts, long long* total) {
  if (!readsInShares(d)) throw std::logic_error("loadParticleShare: only HDF5 particle files are read in shares");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(d.file, ec)) throw InputError("particles.file " + d.file + ": no such file");
  ParticleSet s;
  if constexpr (build::kHdf5) s.positions = readHdf5Particles(d.file, d.dataset, part, parts, total);
  const long long first = (long long)((unsigned long long)*total * unsigned(part) / unsigned(parts));
  if (d.count >= 0 && *total != d.count)
    throw InputError("particles.file " + d.file + ": holds " + std::to_string(*total) +
                     (*total == 1 ? " particle" : " particles") + ", but particles.count is " + std::to_string(d.count));
  checkFinite(s.positions, d.file, first);
  checkMagnitude(s.positions, "particles.file " + d.file, first);
  return s;
}

ParticleSet loadParticles(const ParticleDesc& d) {
  if (d.file.empty()) {
    if (d.procedural == "none") return {};
    ParticleSet s = proceduralParticles(d.procedural,
                                        d.count < 0 ? kDefaultProceduralCount : d.count, d.spacing);
    checkMagnitude(s.positions, "particles.procedural " + d.procedural +
                                    " with particles.spacing " + std::to_string(d.spacing));
    return s;
  }
  std::string format = formatOf(d);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(d.file, ec))
    throw InputError("particles.file " + d.file + ": no such file");
  const std::string hint = d.format == "auto" ? "; read as raw because of its extension (set "
                                                "particles.format for csv or vtk)"
                                              : "";
  ParticleSet s;
  if (format == "raw") {
    auto size = static_cast<long long>(std::filesystem::file_size(d.file, ec));
    if (ec) throw InputError("particles.file " + d.file + ": cannot read its size");
    checkRawSize(size, d.file, d.count, hint);  // before reading a file of the wrong size
    s.positions = parseRawParticles(readWholeFile(d.file, std::ios::binary), d.file, d.count, hint);
  }
  if (format == "csv") s.positions = parseCsvParticles(readWholeFile(d.file, std::ios::in), d.file, d.count);
  if (format == "vtk") {
    if constexpr (build::kVtk) s.positions = readVtkParticles(d.file);
    checkLoaded(s.positions, d.file, d.count);
  }
  if (format == "hdf5") {
    if constexpr (build::kHdf5) s.positions = readHdf5Particles(d.file, d.dataset);
    checkLoaded(s.positions, d.file, d.count);
  }
  return s;
}

std::vector<glm::vec3> parseRawParticles(std::string_view bytes, const std::string& file,
                                         long long declared, const std::string& hint) {
  checkRawSize(static_cast<long long>(bytes.size()), file, declared, hint);
  std::vector<glm::vec3> out(bytes.size() / 12);
  for (size_t i = 0; i < out.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      unsigned char b[4];
      for (int k = 0; k < 4; ++k)
        b[k] = static_cast<unsigned char>(
            bytes[12 * i + 4 * a + (std::endian::native == std::endian::little ? k : 3 - k)]);
      std::memcpy(&out[i][a], b, 4);
    }
  checkLoaded(out, file, declared);
  return out;
}

std::vector<glm::vec3> parseCsvParticles(std::string_view text, const std::string& file,
                                         long long declared) {
  std::vector<glm::vec3> out = readCsv(text, file);
  checkLoaded(out, file, declared);
  return out;
}

Box3 fieldBoundInside(const Box3& clip, const std::vector<glm::vec3>& particles, double h) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::vec3& p : particles) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  return intersect(clip, Box3{lo - h, hi + h});
}

std::vector<glm::vec3> particlesNear(const std::vector<glm::vec3>& all, const Box3& box,
                                     double margin) {
  std::vector<glm::vec3> out;
  const double m2 = margin * margin;
  for (const glm::vec3& p : all) {
    glm::dvec3 q(p);
    glm::dvec3 d = glm::max(glm::max(box.lo - q, q - box.hi), glm::dvec3(0.0));
    if (margin >= 0.0 && glm::dot(d, d) <= m2) out.push_back(p);
  }
  return out;
}

}  // namespace sortlast

namespace sortlast {

NeighbourCount countNeighbours(const std::vector<glm::vec3>& ps, double h, size_t max_sampled) {
  NeighbourCount out;
  if (ps.empty() || !(h > 0.0)) return out;
  // Cells of edge h (at most about 2 per particle; coarser for sparse or huge boxes): every
  // neighbour within h lies in the 27 cells around a particle's own.
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::vec3& p : ps) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
  double cell = h;
  glm::dvec3 n;
  for (;;) {
    n = glm::floor((hi - lo) / cell) + 1.0;
    if (n.x * n.y * n.z <= 2.0 * double(ps.size()) + 1024.0) break;
    cell *= 1.5;
  }
  const glm::ivec3 dims(n);
  auto cellOf = [&](const glm::vec3& p) {
    return glm::clamp(glm::ivec3(glm::floor((glm::dvec3(p) - lo) / cell)), glm::ivec3(0), dims - 1);
  };
  auto index = [&](const glm::ivec3& c) { return (size_t(c.z) * dims.y + c.y) * dims.x + c.x; };
  std::vector<uint32_t> offsets(size_t(dims.x) * dims.y * dims.z + 1, 0), items(ps.size());
  for (const glm::vec3& p : ps) ++offsets[index(cellOf(p)) + 1];
  for (size_t c = 0; c + 1 < offsets.size(); ++c) offsets[c + 1] += offsets[c];
  std::vector<uint32_t> cursor(offsets.begin(), offsets.end() - 1);
  for (size_t i = 0; i < ps.size(); ++i) items[cursor[index(cellOf(ps[i]))]++] = uint32_t(i);
  const size_t stride = std::max<size_t>(1, (ps.size() + max_sampled - 1) / std::max<size_t>(1, max_sampled));
  const double h2 = h * h;
  for (size_t i = 0; i < ps.size(); i += stride) {
    const glm::ivec3 c = cellOf(ps[i]);
    const glm::ivec3 a = glm::max(c - 1, glm::ivec3(0)), b = glm::min(c + 1, dims - 1);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) {
          const size_t k = index(glm::ivec3(x, y, z));
          for (uint32_t e = offsets[k]; e < offsets[k + 1]; ++e) {
            const uint32_t j = items[e];
            if (j == i) continue;
            glm::dvec3 v = glm::dvec3(ps[j]) - glm::dvec3(ps[i]);
            if (glm::dot(v, v) < h2) out.neighbours += 1.0;
          }
        }
    out.sampled += 1.0;
  }
  return out;
}

void resolveAutoSmoothing(ParticleDesc& desc, const NeighbourCount& count, bool in_situ) {
  char why[256];
  if (desc.smoothing != Smoothing::kAuto) {
    desc.smoothing_reason = std::string("set: particles.smoothing: ") + std::string(nameOf(desc.smoothing));
    return;
  }
  const double mean = count.sampled > 0 ? count.neighbours / count.sampled : 0.0;
  if (in_situ) {
    desc.smoothing = Smoothing::kNone;
    desc.smoothing_reason = "auto: none (in situ draws round metaballs only)";
  } else if (desc.method == ParticleMethod::kBillboards) {
    desc.smoothing = Smoothing::kNone;
    desc.smoothing_reason = "auto: none (particles.method: billboards draws round metaballs only)";
  } else if (mean >= kAutoSmoothingNeighbours) {
    desc.smoothing = Smoothing::kAnisotropic;
    std::snprintf(why, sizeof why,
                  "auto: anisotropic (%.1f neighbours within h on average, at least %g: spacing below "
                  "the kernel radius, as SPH output)",
                  mean, kAutoSmoothingNeighbours);
    desc.smoothing_reason = why;
  } else {
    desc.smoothing = Smoothing::kNone;
    std::snprintf(why, sizeof why,
                  "auto: none (%.1f neighbours within h on average, below %g: a sparse set)", mean,
                  kAutoSmoothingNeighbours);
    desc.smoothing_reason = why;
  }
}

}  // namespace sortlast
