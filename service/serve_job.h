#pragma once
// `sortlast serve`: a resident session answering frame requests from HTTP and WebSocket clients.
// Rank 0 runs the front end (service/http_server.h) on its own threads and the frame loop on its
// main thread: it takes the next request (clients in turn, the newest of each), checks it, and
// broadcasts it; every rank renders it; rank 0 encodes the frame and answers. A bad request is
// answered with 4xx and the session goes on; only a lost rank ends it (mpirun then ends the job).
#include <mpi.h>

#include <string>
#include <vector>

namespace sortlast {

struct ServeOptions {
  std::string scene;                   // empty: the built-in default scene
  std::vector<std::string> overrides;  // --set: part of the base scene
  std::string listen = "127.0.0.1:8080";
  std::string token;                   // required unless the address is 127.0.0.1, ::1 or localhost
  std::string token_file;              // --token-file: rank 0 reads the token from it (token_file.h)
  std::string data_dir;                // non-empty: clients may load scene files from under it
  std::string record_dir;              // non-empty: clients may record movies into files under it
  std::string viewer_dir;              // empty: the installed viewer, else the source tree's
  int max_image_side = 4096;
  size_t max_body_bytes = 1 << 20;
  bool quiet = false;
};

// Returns the process exit code. Collective over `comm`. A SIGTERM or SIGINT to rank 0 (or to
// mpirun, which passes SIGINT/SIGTERM on as it ends the job) stops every rank within a second or
// so; one that reaches another rank alone makes it give up after 10 s of rank 0's silence
// (MPI_Abort ends the job).
int runServeJob(const ServeOptions& opts, MPI_Comm comm);

// The web viewer's files: `given`, else installed beside the program or the library
// (PREFIX/share/sortlast/viewer), else the source tree's (a build that was not installed).
std::string findViewerDir(const std::string& given);

}  // namespace sortlast
