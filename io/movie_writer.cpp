#include "io/movie_writer.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <dlfcn.h>

#include <cstdlib>

#include "common/error.h"
#include "common/install_prefix.h"
#include "io/movie_module_abi.h"

namespace sortlast {

namespace {

std::string extensionOf(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

}  // namespace

bool isMoviePath(const std::string& path) {
  const std::string e = extensionOf(path);
  return e == ".mp4" || e == ".webm";
}

int MovieWriter::defaultQuality(const std::string& path) { return extensionOf(path) == ".webm" ? 31 : 23; }
int MovieWriter::maxQuality(const std::string& path) { return extensionOf(path) == ".webm" ? 63 : 51; }
const char* MovieWriter::encoderName(const std::string& path) {
  return extensionOf(path) == ".webm" ? "libvpx-vp9" : "libx264";
}

// The FFmpeg module, loaded once per process on the first movie (io/movie_module_abi.h says why).
namespace {

struct LoadedModule {
  const SortlastMovieApi* api = nullptr;
  std::string error;  // why it could not be loaded (every place tried)
};

// Where the module may be: SORTLAST_MOVIE_MODULE (a file), beside the program (the build tree:
// build/sortlast and build/libsortlast_movie.so), the installed layout (<prefix>/BINDIR/sortlast and
// <prefix>/LIBDIR/sortlast/), and
// the build tree and install prefix configured in (test programs, the Python module).
std::vector<std::string> moduleCandidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("SORTLAST_MOVIE_MODULE"); env && *env) c.push_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    c.push_back((exe.parent_path() / SORTLAST_MOVIE_MODULE_NAME).string());
    const std::filesystem::path prefix = installPrefixOf(exe, SORTLAST_INSTALL_BINDIR);
    if (!prefix.empty())
      c.push_back((prefix / SORTLAST_MOVIE_MODULE_INSTALL_SUBDIR / SORTLAST_MOVIE_MODULE_NAME).string());
  }
  c.push_back(SORTLAST_MOVIE_MODULE_BUILD_PATH);
  c.push_back(SORTLAST_MOVIE_MODULE_INSTALL_PATH);
  return c;
}

const LoadedModule& movieModule() {
  static const LoadedModule module = [] {
    LoadedModule m;
    for (const std::string& path : moduleCandidates()) {
      if (!std::filesystem::exists(path)) {
        m.error += "\n  " + path + ": no such file";
        continue;
      }
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = dlerror();
        m.error += "\n  " + path + ": " + (why ? why : "dlopen failed");
        continue;
      }
      auto entry = reinterpret_cast<const SortlastMovieApi* (*)()>(dlsym(handle, kSortlastMovieApiSymbol));
      const SortlastMovieApi* api = entry ? entry() : nullptr;
      if (!api || api->version != kSortlastMovieApiVersion) {
        m.error += "\n  " + path + ": not this program's movie module (another version)";
        dlclose(handle);
        continue;
      }
      m.api = api;  // kept loaded for the process's life
      m.error.clear();
      break;
    }
    return m;
  }();
  return module;
}

}  // namespace

struct MovieWriter::State {
  const SortlastMovieApi* api = nullptr;
  SortlastMovie* movie = nullptr;
  std::vector<uint8_t> padded;  // the RGB frame at the encoded (even) size
  bool finished = false;
  ~State() {
    if (movie) api->close(movie);
  }
};

int MovieWriter::encodedWidth() const { return (width_ + 1) & ~1; }
int MovieWriter::encodedHeight() const { return (height_ + 1) & ~1; }

MovieWriter::MovieWriter(std::string path, int width, int height, int frame_rate, std::optional<int> quality)
    : path_(std::move(path)), width_(width), height_(height), s_(std::make_unique<State>()) {
  auto fail = [&](const std::string& what) { throw InputError("output " + path_ + ": " + what); };
  const std::string ext = extensionOf(path_);
  const bool webm = ext == ".webm";
  if (ext != ".mp4" && !webm) fail("not a movie container this program writes (.mp4 or .webm)");
  const char* encoder = encoderName(path_);
  const int max_quality = maxQuality(path_);
  const int crf = quality.value_or(defaultQuality(path_));
  if (crf < 0 || crf > max_quality)
    fail("movie.quality " + std::to_string(crf) + " is outside " + encoder + "'s CRF range [0, " +
         std::to_string(max_quality) + "]");
  if (frame_rate < 1) fail("movie.frame_rate must be >= 1");
  const LoadedModule& module = movieModule();
  if (!module.api)
    fail(std::string("movies are written by the module ") + SORTLAST_MOVIE_MODULE_NAME +
         " (FFmpeg), which could not be loaded (set SORTLAST_MOVIE_MODULE to its path):" + module.error);
  s_->api = module.api;
  char err[512] = {0};
  s_->movie = s_->api->open(path_.c_str(), encodedWidth(), encodedHeight(), frame_rate, crf, webm ? 1 : 0,
                            err, sizeof err);
  if (!s_->movie) fail(err);
  s_->padded.resize(size_t(encodedWidth()) * encodedHeight() * 3);
}

MovieWriter::~MovieWriter() = default;

void MovieWriter::addFrame(const std::vector<uint8_t>& rgb) {
  if (rgb.size() != size_t(width_) * height_ * 3)
    throw InputError("output " + path_ + ": a frame of another size than the movie's first");
  const int w = encodedWidth(), h = encodedHeight();
  // Copy into the even-sized frame; an odd side repeats its last column / row.
  for (int y = 0; y < h; ++y) {
    const uint8_t* src = &rgb[size_t(std::min(y, height_ - 1)) * width_ * 3];
    uint8_t* dst = &s_->padded[size_t(y) * w * 3];
    std::copy(src, src + size_t(width_) * 3, dst);
    if (w > width_) std::copy(src + size_t(width_ - 1) * 3, src + size_t(width_) * 3, dst + size_t(width_) * 3);
  }
  char err[512] = {0};
  if (s_->api->add_frame(s_->movie, s_->padded.data(), err, sizeof err) != 0)
    throw InputError("output " + path_ + ": " + err);
}

void MovieWriter::finish() {
  if (s_->finished) return;
  s_->finished = true;
  char err[512] = {0};
  if (s_->api->finish(s_->movie, err, sizeof err) != 0) throw InputError("output " + path_ + ": " + err);
}

}  // namespace sortlast
