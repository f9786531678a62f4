#pragma once
// The boundary between io/movie_writer.cpp and the FFmpeg module (io/movie_module.cpp, built as
// libsortlast_movie.so and loaded with dlopen only when a movie is written).
//
// Why a module: FFmpeg's libavformat and libavcodec pull in about 130 shared libraries (every codec
// Debian builds them with); linked into the program they cost every `sortlast` process about
// 0.1 s of CPU at start (perf stat: an empty program 2.7 ms, the same linking FFmpeg 117 ms), which
// every MPI rank of every run pays, movie or not. Behind dlopen only a movie pays it.
//
// Plain C types only: no exception or C++ type crosses the boundary, so the module and the
// program need not share typeinfo. Each call returns 0 on success or fills `err` (NUL-terminated).
#include <cstddef>
#include <cstdint>

extern "C" {

struct SortlastMovie;  // the module's encoder state

struct SortlastMovieApi {
  int version;  // kSortlastMovieApiVersion
  // An encoder writing `path` (container by webm != 0: WebM/VP9, else MP4/H.264) at an even
  // width x height; crf already checked against the codec's range. Null on failure.
  SortlastMovie* (*open)(const char* path, int width, int height, int frame_rate, int crf, int webm,
                         char* err, size_t err_size);
  // One RGB24 frame of the encoder's (even) size, row 0 at the top.
  int (*add_frame)(SortlastMovie* movie, const uint8_t* rgb, char* err, size_t err_size);
  // Drains the encoder and writes the trailer.
  int (*finish)(SortlastMovie* movie, char* err, size_t err_size);
  void (*close)(SortlastMovie* movie);  // frees it (after finish or not)
};

// The module's one exported symbol.
const SortlastMovieApi* sortlast_movie_api();
}

constexpr int kSortlastMovieApiVersion = 1;
constexpr const char* kSortlastMovieApiSymbol = "sortlast_movie_api";
