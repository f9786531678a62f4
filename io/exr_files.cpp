// OpenEXR's float images (io/image_files.h: writeExr, readExr), compiled only where the build has
// OpenEXR (SORTLAST_WITH_EXR): the callers refuse an .exr name first where it is off.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include "common/error.h"
#include "io/image_files.h"

namespace sortlast::files {

void writeExr(const std::string& path, int width, int height, const std::vector<std::string>& names,
              const std::vector<float>& px) {
  const size_t nc = names.size();
  if (width <= 0 || height <= 0 || nc == 0 || px.size() != size_t(width) * height * nc)
    throw InputError("empty or inconsistent image");
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    const size_t xs = sizeof(float) * nc, ys = xs * size_t(width);
    for (size_t c = 0; c < nc; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(px.data() + c)), xs, ys));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(std::string("OpenEXR: ") + e.what());
  }
}

ImageChannels readExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    ImageChannels img;
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    if (img.width <= 0 || img.height <= 0) throw InputError("empty image");
    for (const char* c : {"R", "G", "B", "A"})
      if (file.header().channels().findChannel(c)) img.names.push_back(c);
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      const std::string n = it.name();
      if (n != "R" && n != "G" && n != "B" && n != "A") img.names.push_back(n);
    }
    img.channels = int(img.names.size());
    img.px.resize(size_t(img.width) * img.height * img.channels);
    const size_t xs = sizeof(float) * img.channels, ys = xs * size_t(img.width);
    // The slice base points at pixel (0, 0) of the data window's coordinates.
    char* base = reinterpret_cast<char*>(img.px.data()) - ptrdiff_t(dw.min.x) * ptrdiff_t(xs) -
                 ptrdiff_t(dw.min.y) * ptrdiff_t(ys);
    Imf::FrameBuffer fb;
    for (int c = 0; c < img.channels; ++c)
      fb.insert(img.names[size_t(c)], Imf::Slice(Imf::FLOAT, base + sizeof(float) * c, xs, ys));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(std::string("OpenEXR: ") + e.what());
  }
}

}  // namespace sortlast::files
