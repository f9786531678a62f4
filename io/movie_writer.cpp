#include "io/movie_writer.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "common/error.h"

namespace sortlast {

namespace {

std::string extensionOf(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::string avError(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, buf, sizeof buf);
  return buf;
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

struct MovieWriter::State {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  std::vector<uint8_t> padded;  // the RGB frame at the encoded (even) size
  int64_t next_pts = 0;
  bool header_written = false, finished = false;

  ~State() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
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

  // libx264 prints its settings and statistics at FFmpeg's default level: errors only.
  av_log_set_level(AV_LOG_ERROR);
  int rc = avformat_alloc_output_context2(&s_->format, nullptr, webm ? "webm" : "mp4", path_.c_str());
  if (rc < 0 || !s_->format) fail("FFmpeg has no " + ext + " muxer (" + avError(rc) + ")");
  const AVCodec* codec = avcodec_find_encoder_by_name(encoder);
  if (!codec) fail(std::string("this FFmpeg's libavcodec has no ") + encoder + " encoder");
  s_->stream = avformat_new_stream(s_->format, nullptr);
  s_->codec = avcodec_alloc_context3(codec);
  if (!s_->stream || !s_->codec) fail("out of memory opening the encoder");
  AVCodecContext* c = s_->codec;
  c->width = encodedWidth();
  c->height = encodedHeight();
  c->time_base = AVRational{1, frame_rate};
  c->framerate = AVRational{frame_rate, 1};
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->gop_size = std::max(1, frame_rate * 2);  // a key frame every two seconds: seeking stays cheap
  c->thread_count = 1;  // the writer thread is one thread; the ranks' renderers have the cores
  if (s_->format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set_int(c->priv_data, "crf", crf, 0);
  if (webm) {
    // libvpx's constant-quality mode is CRF with no bit-rate target (b = 0); "good" deadline at
    // cpu-used 4, libvpx's faster end of good quality.
    c->bit_rate = 0;
    av_opt_set(c->priv_data, "deadline", "good", 0);
    av_opt_set_int(c->priv_data, "cpu-used", 4, 0);
  }
  rc = avcodec_open2(c, codec, nullptr);
  if (rc < 0) fail(std::string("cannot open ") + encoder + ": " + avError(rc));
  rc = avcodec_parameters_from_context(s_->stream->codecpar, c);
  if (rc < 0) fail("cannot set the stream's parameters: " + avError(rc));
  s_->stream->time_base = c->time_base;
  rc = avio_open(&s_->format->pb, path_.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) fail("cannot open for writing: " + avError(rc));
  rc = avformat_write_header(s_->format, nullptr);
  if (rc < 0) fail("cannot write the header: " + avError(rc));
  s_->header_written = true;

  s_->frame = av_frame_alloc();
  s_->packet = av_packet_alloc();
  if (!s_->frame || !s_->packet) fail("out of memory");
  s_->frame->format = c->pix_fmt;
  s_->frame->width = c->width;
  s_->frame->height = c->height;
  rc = av_frame_get_buffer(s_->frame, 0);
  if (rc < 0) fail("cannot allocate a frame: " + avError(rc));
  s_->sws = sws_getContext(c->width, c->height, AV_PIX_FMT_RGB24, c->width, c->height, c->pix_fmt,
                           SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!s_->sws) fail("libswscale cannot convert RGB24 to yuv420p");
  s_->padded.resize(size_t(c->width) * c->height * 3);
}

MovieWriter::~MovieWriter() = default;

namespace {

// Sends `frame` (null: the end) and writes every packet the encoder has ready.
void encode(AVFormatContext* format, AVCodecContext* c, AVStream* st, AVFrame* frame, AVPacket* pkt,
            const std::string& path) {
  int rc = avcodec_send_frame(c, frame);
  if (rc < 0) throw InputError("output " + path + ": encoding failed: " + avError(rc));
  while ((rc = avcodec_receive_packet(c, pkt)) >= 0) {
    av_packet_rescale_ts(pkt, c->time_base, st->time_base);
    pkt->stream_index = st->index;
    rc = av_interleaved_write_frame(format, pkt);
    if (rc < 0) throw InputError("output " + path + ": writing failed: " + avError(rc));
  }
  if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF)
    throw InputError("output " + path + ": encoding failed: " + avError(rc));
}

}  // namespace

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
  int rc = av_frame_make_writable(s_->frame);
  if (rc < 0) throw InputError("output " + path_ + ": " + avError(rc));
  const uint8_t* in[1] = {s_->padded.data()};
  const int stride[1] = {w * 3};
  sws_scale(s_->sws, in, stride, 0, h, s_->frame->data, s_->frame->linesize);
  s_->frame->pts = s_->next_pts++;
  encode(s_->format, s_->codec, s_->stream, s_->frame, s_->packet, path_);
}

void MovieWriter::finish() {
  if (s_->finished) return;
  s_->finished = true;
  encode(s_->format, s_->codec, s_->stream, nullptr, s_->packet, path_);
  const int rc = av_write_trailer(s_->format);
  if (rc < 0) throw InputError("output " + path_ + ": cannot write the trailer: " + avError(rc));
  avio_closep(&s_->format->pb);
}

}  // namespace sortlast
