#pragma once
// The header of a NRRD file (teem's "nearly raw raster data": http://teem.sourceforge.net/nrrd/
// format.html), parsed by us: it is a few text lines, and we read the samples ourselves per brick.
// What sortlast takes: dimension 3; type uchar/uint8, short/int16, ushort/uint16, float, double;
// encoding raw or gzip; endian; sizes; spacings or axis-aligned space directions; space origin;
// data file (detached .nhdr), line skip, byte skip. Everything else a header may say that would
// change the samples' meaning (other types, block type, ascii/hex/bzip2 encodings, other
// dimensions, rotated space directions, data file lists) is refused naming the field; fields
// that do not (content, kinds, centers, labels, units, min/max, space, key/value pairs `k:=v`) are
// read past. An unknown field is refused, as teem does.
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "io/volume_source.h"

namespace sortlast {

struct NrrdHeader {
  SampleType type = SampleType::kUint8;
  glm::ivec3 sizes{0};
  bool big_endian = false;
  bool gzip = false;
  glm::dvec3 spacing{1.0};
  std::optional<glm::dvec3> origin;  // space origin
  std::string data_file;             // detached data (as written; relative to the header's folder)
  int line_skip = 0;                 // lines of the data file (or after the header) to skip
  long long byte_skip = 0;           // bytes to skip after the lines (raw: -1 = the data ends the file)
  long long header_bytes = 0;        // attached data: bytes of the header, its blank line included
};

// Parses a header from the text of a file (`text` may hold the whole file or its first bytes; the
// header ends at the first empty line, or at the end of `text` for a detached header). Throws
// InputError starting with "volume.file FILE: NRRD field 'NAME': ...".
NrrdHeader parseNrrdHeader(const std::string& text, const std::string& file);

// Reads the header of a .nrrd or .nhdr file (its first 64 KiB at most) and parses it.
NrrdHeader readNrrdHeader(const std::string& file);

}  // namespace sortlast
