#include "io/image_files.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <jpeglib.h>
#include <png.h>

#include "common/error.h"

// Every function here throws InputError with a message that names no file: the callers say which
// file and what it was for ("output F: ...", "image F: ..."). libpng and libjpeg report errors
// through a callback that must not return; ours throws, which unwinds through their C frames
// (Debian builds them with unwind tables, as GCC does by default on x86-64).

namespace sortlast::files {

Format formatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".png") return Format::png;
  if (ext == ".jpg" || ext == ".jpeg") return Format::jpeg;
  if (ext == ".exr") return Format::exr;
  if (ext == ".ppm") return Format::ppm;
  return Format::other;
}

std::string readFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(what + " " + path + ": cannot open (" + std::strerror(errno) + ")");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(what + " " + path + ": read error");
  return s.str();
}

void writeFile(const std::string& path, const std::string& bytes, const std::string& what) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(what + " " + path + ": cannot create (" + std::strerror(errno) + ")");
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) throw InputError(what + " " + path + ": write error");
}

namespace {

void checkPixels(const Pixels8& img, int want_channels_min, int want_channels_max) {
  if (img.width <= 0 || img.height <= 0 || img.channels < want_channels_min ||
      img.channels > want_channels_max ||
      img.px.size() != size_t(img.width) * img.height * img.channels)
    throw InputError("empty or inconsistent image (" + std::to_string(img.width) + "x" +
                     std::to_string(img.height) + "x" + std::to_string(img.channels) + ")");
}

// ---- PNG (libpng) ----

[[noreturn]] void pngError(png_structp, png_const_charp msg) { throw InputError(std::string("PNG: ") + msg); }
void pngWarning(png_structp, png_const_charp) {}

void pngWrite(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), n);
}
void pngFlush(png_structp) {}

struct PngRead {
  const std::string* bytes;
  size_t at = 0;
};
void pngRead(png_structp png, png_bytep data, png_size_t n) {
  auto* in = static_cast<PngRead*>(png_get_io_ptr(png));
  if (in->bytes->size() - in->at < n) png_error(png, "file is truncated");
  std::memcpy(data, in->bytes->data() + in->at, n);
  in->at += n;
}

Pixels8 decodePng(const std::string& bytes) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
  if (!png) throw InputError("PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  struct Guard {
    png_structp* p;
    png_infop* i;
    ~Guard() { png_destroy_read_struct(p, i, nullptr); }
  } guard{&png, &info};
  if (!info) throw InputError("PNG: out of memory");
  PngRead src{&bytes};
  png_set_read_fn(png, &src, pngRead);
  png_read_info(png, info);
  // Everything to 8-bit RGBA: expand palettes and low bit depths, keep the high byte of 16-bit
  // samples, grey to RGB, and an opaque alpha where the file has none.
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  Pixels8 img;
  img.width = int(png_get_image_width(png, info));
  img.height = int(png_get_image_height(png, info));
  img.channels = 4;
  if (png_get_rowbytes(png, info) != size_t(img.width) * 4) throw InputError("PNG: unexpected row layout");
  img.px.resize(size_t(img.width) * img.height * 4);
  std::vector<png_bytep> rows(size_t(img.height));
  for (int y = 0; y < img.height; ++y) rows[size_t(y)] = &img.px[size_t(y) * img.width * 4];
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  return img;
}

// ---- JPEG (libjpeg-turbo) ----

[[noreturn]] void jpegError(j_common_ptr cinfo) {
  char msg[JMSG_LENGTH_MAX];
  (*cinfo->err->format_message)(cinfo, msg);
  throw InputError(std::string("JPEG: ") + msg);
}
void jpegSilence(j_common_ptr, int) {}

Pixels8 decodeJpeg(const std::string& bytes) {
  jpeg_decompress_struct cinfo;
  jpeg_error_mgr err;
  cinfo.err = jpeg_std_error(&err);
  err.error_exit = jpegError;
  err.emit_message = jpegSilence;
  jpeg_create_decompress(&cinfo);
  struct Guard {
    jpeg_decompress_struct* c;
    ~Guard() { jpeg_destroy_decompress(c); }
  } guard{&cinfo};
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  jpeg_read_header(&cinfo, TRUE);
  cinfo.out_color_space = JCS_RGB;  // grey and YCbCr alike
  jpeg_start_decompress(&cinfo);
  Pixels8 img;
  img.width = int(cinfo.output_width);
  img.height = int(cinfo.output_height);
  img.channels = 4;
  img.px.assign(size_t(img.width) * img.height * 4, 255);
  std::vector<uint8_t> row(size_t(img.width) * 3);
  while (cinfo.output_scanline < cinfo.output_height) {
    const int y = int(cinfo.output_scanline);
    JSAMPROW r = row.data();
    jpeg_read_scanlines(&cinfo, &r, 1);
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) img.px[(size_t(y) * img.width + x) * 4 + c] = row[size_t(x) * 3 + c];
  }
  jpeg_finish_decompress(&cinfo);
  return img;
}

}  // namespace

std::string encodePng(const Pixels8& img, int level, bool sub_filter) {
  checkPixels(img, 3, 4);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
  if (!png) throw InputError("PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  struct Guard {
    png_structp* p;
    png_infop* i;
    ~Guard() { png_destroy_write_struct(p, i); }
  } guard{&png, &info};
  if (!info) throw InputError("PNG: out of memory");
  std::string out;
  png_set_write_fn(png, &out, pngWrite, pngFlush);
  png_set_IHDR(png, info, png_uint_32(img.width), png_uint_32(img.height), 8,
               img.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, level);
  if (sub_filter) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_write_info(png, info);
  const size_t stride = size_t(img.width) * img.channels;
  for (int y = 0; y < img.height; ++y)
    png_write_row(png, const_cast<png_bytep>(&img.px[size_t(y) * stride]));
  png_write_end(png, nullptr);
  return out;
}

std::string encodeJpeg(const Pixels8& rgb, int quality) {
  checkPixels(rgb, 3, 3);
  jpeg_compress_struct cinfo;
  jpeg_error_mgr err;
  cinfo.err = jpeg_std_error(&err);
  err.error_exit = jpegError;
  err.emit_message = jpegSilence;
  jpeg_create_compress(&cinfo);
  unsigned char* buf = nullptr;
  unsigned long size = 0;
  struct Guard {
    jpeg_compress_struct* c;
    unsigned char** b;
    ~Guard() {
      jpeg_destroy_compress(c);
      std::free(*b);
    }
  } guard{&cinfo, &buf};
  jpeg_mem_dest(&cinfo, &buf, &size);
  cinfo.image_width = JDIMENSION(rgb.width);
  cinfo.image_height = JDIMENSION(rgb.height);
  cinfo.input_components = 3;
  cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(&rgb.px[size_t(cinfo.next_scanline) * rgb.width * 3]);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  return std::string(reinterpret_cast<const char*>(buf), size);
}

Pixels8 decodeRGBA8(const std::string& bytes, const std::string& name_for_errors) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0) return decodePng(bytes);
  if (bytes.size() >= 3 && uint8_t(bytes[0]) == 0xFF && uint8_t(bytes[1]) == 0xD8 && uint8_t(bytes[2]) == 0xFF)
    return decodeJpeg(bytes);
  if (bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] == '6' && std::isspace(static_cast<unsigned char>(bytes[2])))
    return decodePpm(bytes);
  throw InputError("not a PNG, JPEG or PPM file" +
                   (name_for_errors.empty() ? std::string() : " (" + name_for_errors + ")"));
}

}  // namespace sortlast::files
