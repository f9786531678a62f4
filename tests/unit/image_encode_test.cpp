// Frames encoded in memory for the service (io/image_encode.h) look like the files
// `sortlast render` writes.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

#include "common/build_features.h"
#include "common/error.h"
#include "io/image.h"
#include "io/image_encode.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

namespace fs = std::filesystem;

// A premultiplied frame with smooth colour, partial alpha and a transparent border, like a
// rendered volume over an empty background.
ImageRGBA8 testFrame(int w, int h) {
  ImageRGBA8 img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.at(x, y);
      double dx = (x - w / 2.0) / (w / 2.0), dy = (y - h / 2.0) / (h / 2.0);
      double a = std::max(0.0, 1.0 - std::sqrt(dx * dx + dy * dy) * 1.2);
      p[3] = uint8_t(std::lround(a * 255));
      p[0] = uint8_t(std::lround(a * 255 * x / (w - 1.0)));
      p[1] = uint8_t(std::lround(a * 255 * y / (h - 1.0)));
      p[2] = uint8_t(std::lround(a * 128));
    }
  return img;
}

class ImageEncode : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("sortlast_image_encode_test_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string save(const std::string& name, const std::string& bytes) {
    std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  fs::path dir_;
  glm::dvec3 bg_{0.1, 0.2, 0.3};
};

TEST_F(ImageEncode, PngEqualsWriteImage) {
  ImageRGBA8 frame = testFrame(97, 61);  // odd sizes: no row padding assumptions
  std::string file = (dir_ / "written.png").string();
  writeImage(file, frame, bg_);
  std::string png = encodeImage(frame, bg_, "png", 0);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  ImageRGBA8 a = readImageRGBA8(file), b = readImageRGBA8(save("encoded.png", png));
  ASSERT_EQ(b.width, 97);
  ASSERT_EQ(b.height, 61);
  EXPECT_EQ(a.px, b.px);
  for (size_t i = 3; i < b.px.size(); i += 4) ASSERT_EQ(b.px[i], 255) << "opaque";
}

TEST_F(ImageEncode, JpegDecodesCloseToPng) {
  ImageRGBA8 frame = testFrame(128, 96);
  ImageRGBA8 png = readImageRGBA8(save("ref.png", encodeImage(frame, bg_, "png", 0)));
  std::string jpeg = encodeImage(frame, bg_, "jpeg", 90);
  ASSERT_GT(jpeg.size(), 4u);
  EXPECT_EQ(uint8_t(jpeg[0]), 0xFF);
  EXPECT_EQ(uint8_t(jpeg[1]), 0xD8);
  ImageRGBA8 dec = readImageRGBA8(save("enc.jpg", jpeg));
  ASSERT_EQ(dec.width, 128);
  ASSERT_EQ(dec.height, 96);
  double sum = 0;
  int worst = 0;
  for (size_t i = 0; i < dec.px.size(); ++i) {
    if (i % 4 == 3) continue;
    int d = std::abs(int(dec.px[i]) - int(png.px[i]));
    sum += d;
    worst = std::max(worst, d);
  }
  EXPECT_LT(sum / (dec.px.size() * 3 / 4), 2.0);
  EXPECT_LT(worst, 40);
  // Lower quality, smaller file.
  EXPECT_LT(encodeImage(frame, bg_, "jpeg", 20).size(), jpeg.size());
}

TEST_F(ImageEncode, RefusesBadFormatAndQuality) {
  ImageRGBA8 frame = testFrame(8, 8);
  EXPECT_NE(inputErrorOf([&] { encodeImage(frame, bg_, "gif", 90); }).find("gif"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { encodeImage(frame, bg_, "jpeg", 0); }).find("quality"),
            std::string::npos);
  EXPECT_NE(inputErrorOf([&] { encodeImage(frame, bg_, "jpeg", 101); }).find("quality"),
            std::string::npos);
}

// An .exr frame is read as stored before its 8-bit conversion, so a NaN or Inf (which the
// conversion would turn into a plausible 0 or 255) is an error naming the file and pixel.
TEST_F(ImageEncode, ReadingAFloatFrameRefusesNonFiniteValues) {
  if (!build::kExr) GTEST_SKIP() << "this build has no OpenEXR (SORTLAST_WITH_EXR)";
  ImageF frame(5, 4);
  for (size_t i = 0; i < frame.px.size(); ++i) frame.px[i] = 0.1f * float(i % 7);
  const std::string ok = (dir_ / "finite.exr").string();
  writeImage(ok, frame, bg_);
  ImageRGBA8 back = readImageRGBA8(ok);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 4);
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    ImageF f = frame;
    f.px[4 * (2 * 5 + 3) + 1] = bad;  // pixel (3, 2), green
    const std::string path = (dir_ / "bad.exr").string();
    writeImage(path, f, bg_);
    try {
      readImageRGBA8(path);
      FAIL() << "a non-finite value was read without an error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("1 non-finite"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("(3, 2)"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sortlast
