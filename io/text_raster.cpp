#include "io/text_raster.h"

#include <algorithm>
#include <filesystem>

#include <ft2build.h>
#include FT_FREETYPE_H

#include "common/error.h"

namespace sortlast {

struct TextRaster::Face {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Face() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

TextRaster::TextRaster(int pixel_size, const std::string& font_path) : face_(std::make_unique<Face>()) {
  if (!std::filesystem::exists(font_path))
    throw InputError("legend font " + font_path + ": no such file (install Debian's fonts-dejavu-core)");
  if (FT_Init_FreeType(&face_->library) != 0) throw InputError("legend: FreeType cannot start");
  if (FT_New_Face(face_->library, font_path.c_str(), 0, &face_->face) != 0)
    throw InputError("legend font " + font_path + ": FreeType cannot read it as a font");
  if (FT_Set_Pixel_Sizes(face_->face, 0, FT_UInt(std::max(4, pixel_size))) != 0)
    throw InputError("legend font " + font_path + ": no size " + std::to_string(pixel_size));
}

TextRaster::~TextRaster() = default;

int TextRaster::lineHeight() const {
  const FT_Size_Metrics& m = face_->face->size->metrics;
  return int((m.ascender - m.descender) >> 6);
}

namespace {

// UTF-8 to code points (invalid bytes are taken as Latin-1).
std::vector<uint32_t> codePoints(const std::string& s) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
    if (i + size_t(extra) >= s.size() + (extra ? 0 : 1)) extra = 0;
    uint32_t cp = extra == 0 ? c : c & (0x3F >> extra);
    for (int k = 1; k <= extra; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + size_t(k)]) & 0x3F);
    out.push_back(cp);
    i += size_t(extra) + 1;
  }
  return out;
}

}  // namespace

TextMask TextRaster::render(const std::string& text) const {
  FT_Face f = face_->face;
  const FT_Size_Metrics& m = f->size->metrics;
  TextMask out;
  out.baseline = int(m.ascender >> 6);
  out.height = lineHeight();
  const std::vector<uint32_t> cps = codePoints(text);
  // First pass: the width (pen advance with kerning, and the last glyph's ink).
  struct Placed {
    int x;
    FT_UInt glyph;
  };
  std::vector<Placed> placed;
  long pen = 0;  // 26.6
  FT_UInt previous = 0;
  int width = 0;
  for (uint32_t cp : cps) {
    const FT_UInt g = FT_Get_Char_Index(f, cp);
    if (previous && g && FT_HAS_KERNING(f)) {
      FT_Vector k;
      FT_Get_Kerning(f, previous, g, FT_KERNING_DEFAULT, &k);
      pen += k.x;
    }
    if (FT_Load_Glyph(f, g, FT_LOAD_DEFAULT) != 0) continue;
    placed.push_back({int(pen >> 6), g});
    width = std::max(width, int((pen + f->glyph->advance.x) >> 6));
    pen += f->glyph->advance.x;
    previous = g;
  }
  out.width = std::max(1, width + 1);
  out.coverage.assign(size_t(out.width) * out.height, 0);
  for (const Placed& p : placed) {
    if (FT_Load_Glyph(f, p.glyph, FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot s = f->glyph;
    const FT_Bitmap& b = s->bitmap;
    for (unsigned r = 0; r < b.rows; ++r)
      for (unsigned c = 0; c < b.width; ++c) {
        const int x = p.x + s->bitmap_left + int(c), y = out.baseline - s->bitmap_top + int(r);
        if (x < 0 || y < 0 || x >= out.width || y >= out.height) continue;
        uint8_t& dst = out.coverage[size_t(y) * out.width + size_t(x)];
        dst = std::max(dst, b.buffer[size_t(r) * size_t(std::abs(b.pitch)) + c]);
      }
  }
  return out;
}

}  // namespace sortlast
