// libsortlast_movie.so: the FFmpeg encoder behind io/movie_writer.h (the boundary and why it is a
// module: io/movie_module_abi.h). libavformat muxes, libavcodec encodes (libx264 or libvpx-vp9),
// libswscale converts RGB24 to the codecs' 4:2:0 YUV.
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "io/movie_module_abi.h"

struct SortlastMovie {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  int64_t next_pts = 0;

  ~SortlastMovie() {
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

namespace {

// A failure inside the module: its message goes back through `err`.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string avError(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

void copyError(const char* what, char* err, size_t err_size) {
  if (err_size == 0) return;
  std::snprintf(err, err_size, "%s", what);
}

// Sends `frame` (null: the end) and writes every packet the encoder has ready.
void encode(SortlastMovie& m, AVFrame* frame) {
  int rc = avcodec_send_frame(m.codec, frame);
  if (rc < 0) throw Failure("encoding failed: " + avError(rc));
  while ((rc = avcodec_receive_packet(m.codec, m.packet)) >= 0) {
    // libx264 leaves the duration 0; the MP4 muxer then gives the last sample no time and ends
    // the edit list at its start, so players drop the last frame wherever the list's rounding to
    // milliseconds does not happen to cover it (3 frames at 10 frames/s decoded as 2).
    if (m.packet->duration <= 0) m.packet->duration = 1;  // one frame, in the codec's time base
    av_packet_rescale_ts(m.packet, m.codec->time_base, m.stream->time_base);
    m.packet->stream_index = m.stream->index;
    rc = av_interleaved_write_frame(m.format, m.packet);
    if (rc < 0) throw Failure("writing failed: " + avError(rc));
  }
  if (rc != AVERROR(EAGAIN) && rc != AVERROR_EOF) throw Failure("encoding failed: " + avError(rc));
}

void openMovie(SortlastMovie& m, const char* path, int width, int height, int frame_rate, int crf, bool webm) {
  const char* encoder = webm ? "libvpx-vp9" : "libx264";
  // libx264 prints its settings and statistics at FFmpeg's default level: errors only.
  av_log_set_level(AV_LOG_ERROR);
  int rc = avformat_alloc_output_context2(&m.format, nullptr, webm ? "webm" : "mp4", path);
  if (rc < 0 || !m.format)
    throw Failure(std::string("FFmpeg has no ") + (webm ? ".webm" : ".mp4") + " muxer (" + avError(rc) + ")");
  const AVCodec* codec = avcodec_find_encoder_by_name(encoder);
  if (!codec) throw Failure(std::string("this FFmpeg's libavcodec has no ") + encoder + " encoder");
  m.stream = avformat_new_stream(m.format, nullptr);
  m.codec = avcodec_alloc_context3(codec);
  if (!m.stream || !m.codec) throw Failure("out of memory opening the encoder");
  AVCodecContext* c = m.codec;
  c->width = width;
  c->height = height;
  c->time_base = AVRational{1, frame_rate};
  c->framerate = AVRational{frame_rate, 1};
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->gop_size = frame_rate * 2 > 1 ? frame_rate * 2 : 1;  // a key frame every two seconds: seeking stays cheap
  c->thread_count = 1;  // the writer thread is one thread; the ranks' renderers have the cores
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set_int(c->priv_data, "crf", crf, 0);
  if (webm) {
    // libvpx's constant-quality mode is CRF with no bit-rate target (b = 0); "good" deadline at
    // cpu-used 4, libvpx's faster end of good quality.
    c->bit_rate = 0;
    av_opt_set(c->priv_data, "deadline", "good", 0);
    av_opt_set_int(c->priv_data, "cpu-used", 4, 0);
  }
  rc = avcodec_open2(c, codec, nullptr);
  if (rc < 0) throw Failure(std::string("cannot open ") + encoder + ": " + avError(rc));
  rc = avcodec_parameters_from_context(m.stream->codecpar, c);
  if (rc < 0) throw Failure("cannot set the stream's parameters: " + avError(rc));
  m.stream->time_base = c->time_base;
  rc = avio_open(&m.format->pb, path, AVIO_FLAG_WRITE);
  if (rc < 0) throw Failure("cannot open for writing: " + avError(rc));
  rc = avformat_write_header(m.format, nullptr);
  if (rc < 0) throw Failure("cannot write the header: " + avError(rc));

  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
  if (!m.frame || !m.packet) throw Failure("out of memory");
  m.frame->format = c->pix_fmt;
  m.frame->width = c->width;
  m.frame->height = c->height;
  rc = av_frame_get_buffer(m.frame, 0);
  if (rc < 0) throw Failure("cannot allocate a frame: " + avError(rc));
  m.sws = sws_getContext(c->width, c->height, AV_PIX_FMT_RGB24, c->width, c->height, c->pix_fmt,
                         SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!m.sws) throw Failure("libswscale cannot convert RGB24 to yuv420p");
}

SortlastMovie* movieOpen(const char* path, int width, int height, int frame_rate, int crf, int webm,
                         char* err, size_t err_size) {
  SortlastMovie* m = new (std::nothrow) SortlastMovie;
  if (!m) {
    copyError("out of memory", err, err_size);
    return nullptr;
  }
  try {
    openMovie(*m, path, width, height, frame_rate, crf, webm != 0);
    return m;
  } catch (const std::exception& e) {
    copyError(e.what(), err, err_size);
    delete m;
    return nullptr;
  }
}

int movieAddFrame(SortlastMovie* m, const uint8_t* rgb, char* err, size_t err_size) {
  try {
    int rc = av_frame_make_writable(m->frame);
    if (rc < 0) throw Failure(avError(rc));
    const uint8_t* in[1] = {rgb};
    const int stride[1] = {m->codec->width * 3};
    sws_scale(m->sws, in, stride, 0, m->codec->height, m->frame->data, m->frame->linesize);
    m->frame->pts = m->next_pts++;
    encode(*m, m->frame);
    return 0;
  } catch (const std::exception& e) {
    copyError(e.what(), err, err_size);
    return 1;
  }
}

int movieFinish(SortlastMovie* m, char* err, size_t err_size) {
  try {
    encode(*m, nullptr);
    const int rc = av_write_trailer(m->format);
    if (rc < 0) throw Failure("cannot write the trailer: " + avError(rc));
    avio_closep(&m->format->pb);
    return 0;
  } catch (const std::exception& e) {
    copyError(e.what(), err, err_size);
    return 1;
  }
}

void movieClose(SortlastMovie* m) { delete m; }

const SortlastMovieApi kApi = {kSortlastMovieApiVersion, movieOpen, movieAddFrame, movieFinish, movieClose};

}  // namespace

extern "C" __attribute__((visibility("default"))) const SortlastMovieApi* sortlast_movie_api() { return &kApi; }
