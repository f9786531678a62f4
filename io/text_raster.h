#pragma once
// Text as an 8-bit coverage mask, through FreeType in DejaVu Sans (Debian's fonts-dejavu-core, at
// its Debian path): the legend's title and tick labels (session/frame_legend.h). Anti-aliased
// glyphs, advanced and kerned by the font's own metrics, on one line.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sortlast {

// Where fonts-dejavu-core installs DejaVu Sans on Debian.
inline constexpr const char* kLegendFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct TextMask {
  int width = 0, height = 0;  // height: ascent + descent of the font at its size
  int baseline = 0;           // rows from the top to the baseline
  std::vector<uint8_t> coverage;  // width * height, row 0 at the top
};

class TextRaster {
 public:
  // Throws InputError naming the font file (missing: install fonts-dejavu-core) and `pixel_size`.
  explicit TextRaster(int pixel_size, const std::string& font_path = kLegendFontPath);
  ~TextRaster();
  TextRaster(const TextRaster&) = delete;
  TextRaster& operator=(const TextRaster&) = delete;

  TextMask render(const std::string& text) const;  // ASCII and Latin-1 in UTF-8
  int lineHeight() const;

 private:
  struct Face;
  std::unique_ptr<Face> face_;
};

}  // namespace sortlast
