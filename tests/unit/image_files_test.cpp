// The codecs (io/image_files.h): PNG (libpng and our libdeflate writer), JPEG, PPM and EXR round trips, conversions on reading, and
// bad files named in the error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/build_features.h"
#include "common/error.h"
#include "io/image.h"
#include "io/image_files.h"
#include "tests/unit/input_error_of.h"

namespace sortlast {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / ("image_files_" + name)).string();
}

files::Pixels8 gradient(int w, int h, int channels) {
  files::Pixels8 p{w, h, channels, std::vector<uint8_t>(size_t(w) * h * channels)};
  for (size_t i = 0; i < p.px.size(); ++i) p.px[i] = uint8_t((i * 37) % 251);
  return p;
}

TEST(ImageFiles, FormatByExtension) {
  EXPECT_EQ(files::formatOf("a/b.PNG"), files::Format::png);
  EXPECT_EQ(files::formatOf("x.jpeg"), files::Format::jpeg);
  EXPECT_EQ(files::formatOf("x.jpg"), files::Format::jpeg);
  EXPECT_EQ(files::formatOf("x.exr"), files::Format::exr);
  EXPECT_EQ(files::formatOf("x.PPM"), files::Format::ppm);
  EXPECT_EQ(files::formatOf("x.tif"), files::Format::other);
}

TEST(ImageFiles, PngRoundTripsRgbAndRgba) {
  for (int channels : {3, 4})
    for (auto [level, sub] : {std::pair{6, false}, std::pair{1, true}, std::pair{0, false}}) {
      files::Pixels8 in = gradient(7, 5, channels);
      files::Pixels8 out = files::decodeRGBA8(files::encodePng(in, level, sub), "");
      ASSERT_EQ(out.width, 7);
      ASSERT_EQ(out.height, 5);
      ASSERT_EQ(out.channels, 4);
      for (size_t i = 0; i < size_t(7 * 5); ++i)
        for (int c = 0; c < 4; ++c)
          EXPECT_EQ(out.px[4 * i + c], c < channels ? in.px[i * channels + c] : 255) << i << " " << c;
    }
}

// Our PNG writer: libpng reads back every byte, with each row filter, RGB and RGBA, at a width
// whose rows are not a multiple of anything (the filters' first-pixel cases).
TEST(ImageFiles, DeflatePngRoundTripsThroughLibpng) {
  for (int channels : {3, 4})
    for (auto filter : {files::PngFilter::kNone, files::PngFilter::kSub, files::PngFilter::kUp, files::PngFilter::kPaeth})
      for (int level : {0, 2, 12}) {
        files::Pixels8 in = gradient(13, 7, channels);
        files::Pixels8 out = files::decodeRGBA8(files::encodePngDeflate(in, level, filter), "");
        ASSERT_EQ(out.width, 13);
        ASSERT_EQ(out.height, 7);
        for (size_t i = 0; i < size_t(13 * 7); ++i)
          for (int c = 0; c < 4; ++c)
            ASSERT_EQ(out.px[4 * i + c], c < channels ? in.px[i * channels + c] : 255)
                << "pixel " << i << " channel " << c << " filter " << int(filter) << " level " << level;
      }
  EXPECT_NE(inputErrorOf([] { files::encodePngDeflate(gradient(2, 2, 3), 13); }).find("level 13"), std::string::npos);
}

TEST(ImageFiles, PpmRoundTripsAndReadsCommentsInTheHeader) {
  files::Pixels8 in = gradient(5, 3, 3);
  files::Pixels8 out = files::decodeRGBA8(files::encodePpm(in), "");
  ASSERT_EQ(out.width, 5);
  ASSERT_EQ(out.height, 3);
  for (size_t i = 0; i < size_t(5 * 3); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(out.px[4 * i + c], c < 3 ? in.px[i * 3 + c] : 255);
  // Another writer's header: a comment, other whitespace.
  std::string other = "P6 # made elsewhere\n1\t1\n255\n" + std::string("\x01\x02\x03", 3);
  out = files::decodeRGBA8(other, "");
  EXPECT_EQ(out.px, (std::vector<uint8_t>{1, 2, 3, 255}));
  EXPECT_NE(inputErrorOf([] { files::decodeRGBA8("P6\n2 2\n255\nabc", ""); }).find("truncated"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { files::decodeRGBA8("P6\n2 2\n65535\n", ""); }).find("maxval 65535"), std::string::npos);
  EXPECT_NE(inputErrorOf([] { files::decodeRGBA8("P6\nx 2\n255\n", ""); }).find("width"), std::string::npos);
}

TEST(ImageFiles, JpegDecodesCloseToItsInput) {
  files::Pixels8 in{16, 16, 3, std::vector<uint8_t>(16 * 16 * 3, 0)};
  for (size_t i = 0; i < in.px.size(); i += 3) {
    in.px[i] = 200;
    in.px[i + 1] = 100;
    in.px[i + 2] = 50;
  }
  files::Pixels8 out = files::decodeRGBA8(files::encodeJpeg(in, 95), "");
  ASSERT_EQ(out.width, 16);
  for (size_t i = 0; i < size_t(16 * 16); ++i) {
    EXPECT_NEAR(out.px[4 * i], 200, 3);
    EXPECT_NEAR(out.px[4 * i + 1], 100, 3);
    EXPECT_NEAR(out.px[4 * i + 2], 50, 3);
    EXPECT_EQ(out.px[4 * i + 3], 255);
  }
}

TEST(ImageFiles, ExrKeepsEveryFloatAndOrdersColourFirst) {
  if (!build::kExr) GTEST_SKIP() << "this build has no OpenEXR (SORTLAST_WITH_EXR)";
  const std::string path = tempPath("any.exr");
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> px = {1.5f, -2.0f, inf, 3e-30f, 0.0f, 7.0f};  // 3 pixels x 2 channels
  files::writeExr(path, 3, 1, {"z", "G"}, px);
  ImageChannels img = files::readExr(path);
  ASSERT_EQ(img.channels, 2);
  ASSERT_EQ(img.names, (std::vector<std::string>{"G", "z"}));
  for (int x = 0; x < 3; ++x) {
    EXPECT_EQ(img.px[size_t(2 * x)], px[size_t(2 * x + 1)]);  // G
    EXPECT_EQ(img.px[size_t(2 * x + 1)], px[size_t(2 * x)]);  // z
  }
  std::filesystem::remove(path);
}

TEST(ImageFiles, FramesWrittenAndReadThroughImageH) {
  ImageF f(2, 2);
  for (size_t i = 0; i < f.px.size(); ++i) f.px[i] = float(i % 4) / 4.0f;
  for (const char* name : {"frame.png", "frame.exr", "frame.ppm", "frame.jpg"}) {
    if (!build::kExr && std::string(name) == "frame.exr") continue;
    const std::string path = tempPath(name);
    writeImage(path, f, glm::dvec3(0.5));
    ImageRGBA8 back = readImageRGBA8(path);
    const std::vector<uint8_t> want = toRGB8(overBackground(f, glm::dvec3(0.5)));
    // JPEG is lossy: on a 2x2 image of 4 levels, quality 95 stays within a few steps.
    const int tolerance = std::string(name) == "frame.jpg" ? 6 : 0;
    for (size_t i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.px[4 * i + c], want[3 * i + c], tolerance) << name;
    std::filesystem::remove(path);
  }
  EXPECT_NE(inputErrorOf([&] { writeImage(tempPath("frame.tif"), f, glm::dvec3(0)); }).find("no image writer"),
            std::string::npos);
}

// The one-pass conversion of 8-bit frames equals the float path it replaced, bit for bit, for
// every (value, alpha) pair over backgrounds whose products round differently.
TEST(ImageFiles, OpaqueRGB8EqualsTheFloatPath) {
  ImageRGBA8 img(256, 256);
  for (int v = 0; v < 256; ++v)
    for (int a = 0; a < 256; ++a) {
      uint8_t* p = img.at(v, a);
      p[0] = p[1] = p[2] = uint8_t(v);
      p[3] = uint8_t(a);
    }
  // 64 Ki pixels: the table path; a 16-row strip of it (4 Ki pixels): the direct one.
  ImageRGBA8 strip(256, 16);
  std::copy(img.px.begin() + 120 * 256 * 4, img.px.begin() + 136 * 256 * 4, strip.px.begin());
  for (const glm::dvec3 bg : {glm::dvec3(0.0), glm::dvec3(0.3, 0.77, 1.0), glm::dvec3(0.1, 0.5, 0.999)})
    for (const ImageRGBA8* im : {&img, &strip}) {
      const std::vector<uint8_t> want = toRGB8(overBackground(toFloat(*im), bg));
      ASSERT_EQ(opaqueRGB8(*im, bg), want) << bg.x << " " << bg.y << " " << bg.z << " height " << im->height;
    }
}

TEST(ImageFiles, BadFilesAreNamed) {
  const std::string missing = tempPath("missing.png");
  std::string msg = inputErrorOf([&] { readImageRGBA8(missing); });
  EXPECT_NE(msg.find("image " + missing + ": cannot open"), std::string::npos) << msg;

  const std::string text = tempPath("text.png");
  files::writeFile(text, "not an image at all", "test");
  msg = inputErrorOf([&] { readImageRGBA8(text); });
  EXPECT_NE(msg.find("image " + text + ": not a PNG, JPEG or PPM"), std::string::npos) << msg;

  const std::string cut = tempPath("cut.png");
  std::string png = files::encodePng(gradient(40, 40, 3));
  files::writeFile(cut, png.substr(0, png.size() / 2), "test");
  msg = inputErrorOf([&] { readImageRGBA8(cut); });
  EXPECT_NE(msg.find("image " + cut + ": PNG: "), std::string::npos) << msg;

  const std::string bad_exr = tempPath("bad.exr");
  files::writeFile(bad_exr, std::string("\x76\x2f\x31\x01", 4) + "garbage", "test");
  msg = inputErrorOf([&] { readImageRGBA8(bad_exr); });
  // Without OpenEXR the file is refused by the option that builds it.
  EXPECT_NE(msg.find(build::kExr ? "image " + bad_exr + ": OpenEXR: "
                                 : "image " + bad_exr + ": this build has no OpenEXR (configure with -DSORTLAST_WITH_EXR=ON)"),
            std::string::npos)
      << msg;
  for (const auto& p : {text, cut, bad_exr}) std::filesystem::remove(p);
}

}  // namespace
}  // namespace sortlast
