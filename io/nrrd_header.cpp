#include "io/nrrd_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "common/error.h"

namespace sortlast {

namespace {

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct Field {
  const std::string& file;
  std::string name;
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError("volume.file " + file + ": NRRD field '" + name + "': " + why);
  }
};

// Whitespace-separated numbers, exactly n of them, finite.
std::vector<double> numbers(const std::string& value, size_t n, const Field& f) {
  std::istringstream in(value);
  std::vector<double> out;
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') f.fail("'" + word + "' is not a number");
    if (!std::isfinite(v)) f.fail("'" + word + "' is not finite");
    out.push_back(v);
  }
  if (out.size() != n) f.fail("expected " + std::to_string(n) + " numbers, got '" + value + "'");
  return out;
}

long long integer(const std::string& value, const Field& f) {
  char* end = nullptr;
  long long v = std::strtoll(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0') f.fail("expected an integer, got '" + value + "'");
  return v;
}

// "(a,b,c)" vectors, or "none", n of them.
std::vector<std::optional<glm::dvec3>> vectors(const std::string& value, size_t n, const Field& f) {
  std::vector<std::optional<glm::dvec3>> out;
  size_t i = 0;
  while (i < value.size()) {
    while (i < value.size() && std::isspace(static_cast<unsigned char>(value[i]))) ++i;
    if (i >= value.size()) break;
    if (value.compare(i, 4, "none") == 0) {
      out.push_back(std::nullopt);
      i += 4;
      continue;
    }
    if (value[i] != '(') f.fail("expected (x,y,z) vectors, got '" + value + "'");
    size_t close = value.find(')', i);
    if (close == std::string::npos) f.fail("a vector is not closed: '" + value + "'");
    std::string inner = value.substr(i + 1, close - i - 1);
    std::replace(inner.begin(), inner.end(), ',', ' ');
    std::vector<double> v = numbers(inner, 3, f);
    out.push_back(glm::dvec3(v[0], v[1], v[2]));
    i = close + 1;
  }
  if (out.size() != n) f.fail("expected " + std::to_string(n) + " vectors, got '" + value + "'");
  return out;
}

SampleType sampleType(const std::string& value, const Field& f) {
  const std::string v = lower(value);
  if (v == "uchar" || v == "unsigned char" || v == "uint8" || v == "uint8_t") return SampleType::kUint8;
  if (v == "short" || v == "short int" || v == "signed short" || v == "signed short int" ||
      v == "int16" || v == "int16_t")
    return SampleType::kInt16;
  if (v == "ushort" || v == "unsigned short" || v == "unsigned short int" || v == "uint16" ||
      v == "uint16_t")
    return SampleType::kUint16;
  if (v == "float") return SampleType::kFloat32;
  if (v == "double") return SampleType::kFloat64;
  f.fail("type '" + value + "' is not supported (sortlast reads uchar, short, ushort, float, double)");
}

}  // namespace

NrrdHeader parseNrrdHeader(const std::string& text, const std::string& file) {
  NrrdHeader h;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line.rfind("NRRD000", 0) != 0)
    throw InputError("volume.file " + file + ": not a NRRD file (it must start with NRRD0001 ... NRRD0005)");
  long long consumed = (long long)line.size() + 1;
  std::set<std::string> seen;
  bool have_type = false, have_dimension = false, have_sizes = false, have_encoding = false,
       have_endian = false, have_spacings = false, have_directions = false, ended = false;
  while (std::getline(in, line)) {
    consumed += (long long)line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {  // the blank line: attached data follows
      ended = true;
      break;
    }
    if (line[0] == '#') continue;
    const size_t kv = line.find(":=");
    const size_t colon = line.find(": ");
    if (kv != std::string::npos && (colon == std::string::npos || kv < colon)) continue;  // key/value pair
    if (colon == std::string::npos)
      throw InputError("volume.file " + file + ": NRRD header line '" + line +
                       "' is neither 'field: value' nor 'key:=value'");
    Field f{file, lower(trim(line.substr(0, colon)))};
    const std::string value = trim(line.substr(colon + 2));
    if (!seen.insert(f.name).second) f.fail("given twice");
    if (f.name == "type") {
      h.type = sampleType(value, f);
      have_type = true;
    } else if (f.name == "dimension") {
      if (integer(value, f) != 3) f.fail("dimension " + value + " is not supported: sortlast reads 3-D volumes");
      have_dimension = true;
    } else if (f.name == "sizes") {
      std::vector<double> s = numbers(value, 3, f);
      for (int a = 0; a < 3; ++a) {
        if (s[size_t(a)] != std::floor(s[size_t(a)]) || s[size_t(a)] < 1 || s[size_t(a)] > 1048576)
          f.fail("sizes must be integers in [1, 2^20], got '" + value + "'");
        h.sizes[a] = int(s[size_t(a)]);
      }
      have_sizes = true;
    } else if (f.name == "endian") {
      const std::string e = lower(value);
      if (e != "little" && e != "big") f.fail("expected little or big, got '" + value + "'");
      h.big_endian = e == "big";
      have_endian = true;
    } else if (f.name == "encoding") {
      const std::string e = lower(value);
      if (e == "raw") {
        h.gzip = false;
      } else if (e == "gzip" || e == "gz") {
        h.gzip = true;
      } else {
        f.fail("encoding '" + value + "' is not supported (sortlast reads raw and gzip)");
      }
      have_encoding = true;
    } else if (f.name == "spacings") {
      std::vector<double> s = numbers(value, 3, f);
      for (int a = 0; a < 3; ++a) {
        if (!(std::abs(s[size_t(a)]) > 0)) f.fail("spacings must not be 0, got '" + value + "'");
        h.spacing[a] = std::abs(s[size_t(a)]);
      }
      have_spacings = true;
    } else if (f.name == "space directions") {
      auto dirs = vectors(value, 3, f);
      for (int a = 0; a < 3; ++a) {
        if (!dirs[size_t(a)]) f.fail("'none' for a volume axis: sortlast reads 3 spatial axes");
        const glm::dvec3 d = *dirs[size_t(a)];
        for (int b = 0; b < 3; ++b)
          if (b != a && d[b] != 0.0)
            f.fail("axis " + std::to_string(a) + " is not along axis " + std::to_string(a) +
                   " of space: sortlast reads axis-aligned grids only (got '" + value + "')");
        if (!(std::abs(d[a]) > 0)) f.fail("a zero direction for axis " + std::to_string(a));
        h.spacing[a] = std::abs(d[a]);
      }
      have_directions = true;
    } else if (f.name == "space origin") {
      auto o = vectors(value, 1, f);
      if (!o[0]) f.fail("expected (x,y,z)");
      h.origin = *o[0];
    } else if (f.name == "data file" || f.name == "datafile") {
      if (value.rfind("LIST", 0) == 0 || value.find(' ') != std::string::npos)
        f.fail("data split over several files is not supported ('" + value + "')");
      if (value.empty()) f.fail("empty");
      h.data_file = value;
    } else if (f.name == "line skip" || f.name == "lineskip") {
      long long v = integer(value, f);
      if (v < 0 || v > 1000000) f.fail("expected an integer in [0, 10^6], got '" + value + "'");
      h.line_skip = int(v);
    } else if (f.name == "byte skip" || f.name == "byteskip") {
      long long v = integer(value, f);
      if (v < -1) f.fail("expected -1 or an integer >= 0, got '" + value + "'");
      h.byte_skip = v;
    } else if (f.name == "block size" || f.name == "blocksize") {
      f.fail("block types are not supported");
    } else if (f.name == "space dimension" || f.name == "space") {
      // Which space the directions live in: only axis-aligned directions are taken, so any.
    } else if (f.name == "content" || f.name == "kinds" || f.name == "centers" || f.name == "centerings" ||
               f.name == "labels" || f.name == "units" || f.name == "space units" || f.name == "min" ||
               f.name == "max" || f.name == "old min" || f.name == "oldmin" || f.name == "old max" ||
               f.name == "oldmax" || f.name == "thicknesses" || f.name == "axis mins" ||
               f.name == "axismins" || f.name == "axis maxs" || f.name == "axismaxs" ||
               f.name == "sample units" || f.name == "measurement frame" || f.name == "number") {
      // Descriptive: the samples mean the same without them.
    } else {
      f.fail("unknown field");
    }
  }
  const auto missing = [&](const char* name) {
    throw InputError("volume.file " + file + ": NRRD field '" + name + "': required, but missing");
  };
  if (!have_type) missing("type");
  if (!have_dimension) missing("dimension");
  if (!have_sizes) missing("sizes");
  if (!have_encoding) missing("encoding");
  if (!have_endian && sampleTypeBytes(h.type) > 1) missing("endian");
  if (have_spacings && have_directions)
    throw InputError("volume.file " + file + ": NRRD fields 'spacings' and 'space directions' are both given: use one");
  if (h.gzip && h.byte_skip == -1)
    throw InputError("volume.file " + file + ": NRRD field 'byte skip': -1 is for raw encoding only");
  if (h.data_file.empty() && !ended)
    throw InputError("volume.file " + file + ": NRRD header has no blank line before the data, and no 'data file'");
  h.header_bytes = h.data_file.empty() ? consumed : 0;
  return h;
}

NrrdHeader readNrrdHeader(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("volume.file " + file + ": cannot open");
  std::string text(65536, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  // The header is the text up to the first empty line; the data after it may hold any bytes.
  size_t end = text.find("\n\n");
  const size_t crlf = text.find("\r\n\r\n");
  if (crlf != std::string::npos && (end == std::string::npos || crlf < end)) end = crlf + 2;
  if (end != std::string::npos) text.resize(end + 2);
  return parseNrrdHeader(text, file);
}

}  // namespace sortlast
