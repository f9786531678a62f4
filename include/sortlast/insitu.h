#pragma once
// sortlast in situ: render a running MPI simulation from its own memory.
//
//   sortlast::InSitu vis(comm, "actions.yaml");   // collective; throws sortlast::InSituError
//   for (int step = 0; ...; ++step) {
//     simulate(...);
//     sortlast::Published data;
//     data.grid = sortlast::GridBlock{...};        // this rank's piece, where it lies
//     vis.publish(step, time, data);               // collective; no copy of the arrays
//     vis.execute();                               // collective; renders when a trigger fires
//   }
//
// The library never calls MPI_Init or MPI_Finalize and only communicates on the communicator it
// is given (it duplicates it, so its messages never mix with the simulation's). The arrays must
// stay valid and unchanged from publish() to the end of execute(). See docs/insitu.md.
#include <mpi.h>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sortlast {

enum class ElementType { kUint8, kUint16, kInt16, kFloat32, kFloat64 };

// This rank's block of a uniform grid (point samples). Blocks of all ranks tile the global grid
// without overlapping in their owned samples; any decomposition will do (slabs, 2x2x1, uneven),
// and a rank may publish no block (dims 0). Neighbouring blocks need not carry ghost layers:
// sortlast fetches the samples it needs across block faces from the neighbours.
struct GridBlock {
  const void* data = nullptr;              // sample (0, 0, 0) of the array (ghost layers included)
  ElementType type = ElementType::kFloat32;
  std::array<int, 3> dims{0, 0, 0};        // samples per axis in the array, ghosts included
  // Distance in elements between neighbouring samples along x, y, z; all 0: dense, x fastest
  // (strides {1, dims[0], dims[0] * dims[1]}).
  std::array<long long, 3> strides{0, 0, 0};
  std::array<int, 3> ghost_lo{0, 0, 0};    // ghost layers the array carries before its owned samples
  std::array<int, 3> ghost_hi{0, 0, 0};    // ... and after them
  std::array<double, 3> origin{0, 0, 0};   // world position of the first owned (non-ghost) sample
  std::array<double, 3> spacing{1, 1, 1};  // world distance between samples (the same on every rank)
  std::string name = "field";              // the field's name (actions may refer to it)
};

// This rank's particles (metaball centres), where they lie.
struct ParticleBlock {
  const double* x = nullptr;  // positions: x[i * stride], y[i * stride], z[i * stride]
  const double* y = nullptr;
  const double* z = nullptr;
  long long stride = 1;       // in doubles
  long long count = 0;
  const float* x32 = nullptr;  // alternatively float positions (then x, y, z stay null)
  const float* y32 = nullptr;
  const float* z32 = nullptr;
  std::map<std::string, const double*> scalars;  // optional per-particle values (same stride)
};

struct Published {
  GridBlock grid;             // dims 0: no volume on this rank
  ParticleBlock particles;    // count 0: no particles on this rank
  // Named quantities for triggers (`trigger: {when: NAME, crosses: X}`). Every rank must publish
  // the same values: each decides alone, without a message, whether a render fires.
  std::map<std::string, double> quantities;
};

// Bad actions, bad published data with on_error: abort, or a rank that failed.
struct InSituError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What execute() did, for the simulation's log.
struct ExecuteReport {
  bool rendered = false;              // a trigger fired and images were written
  std::vector<std::string> images;    // files written by this call (rank 0)
  std::string error;                  // non-empty: this step's images were skipped (why)
  double seconds = 0;                 // wall time of execute()
  // Host memory sortlast's buffers hold beyond the simulation's arrays on this rank: the ghost
  // shell fetched from neighbours, the conversion chunk, particle copies (not the GL textures).
  double memory_added_mib = 0;
  double texture_mib = 0;             // this rank's brick texture (R32F; host memory on llvmpipe)
  // Where this rank renders (render.device, docs/cluster.md): GL_VENDOR, GL_RENDERER, the
  // hardware EGL device (-1: software) and the host.
  std::string gl_vendor, gl_renderer, host;
  int device = -1;
  // The last image written, its accuracy as estimated while it rendered (render.estimate,
  // docs/volumes.md; rank 0): the estimated PSNR against the exact model and its 95 % bounds
  // (infinity: no difference seen), the share of pixels more than 4/255 off and its 95 % upper
  // bound. NaN where that image has no estimate; accuracy_why then says why (particles in the
  // frame, render.estimate: off, ...).
  double estimated_psnr_db = std::numeric_limits<double>::quiet_NaN();
  double psnr_db_lo = std::numeric_limits<double>::quiet_NaN(), psnr_db_hi = std::numeric_limits<double>::quiet_NaN();
  double over4_share = std::numeric_limits<double>::quiet_NaN(), over4_share_hi = std::numeric_limits<double>::quiet_NaN();
  std::string accuracy_why;
};

class InSitu {
 public:
  // Collective over `comm`. Reads the actions file (YAML, see docs/insitu.md); throws
  // InSituError naming the problem on every rank if it is bad.
  InSitu(MPI_Comm comm, const std::string& actions_file);
  // The actions as YAML text instead of a file.
  static InSitu fromText(MPI_Comm comm, const std::string& actions_yaml);
  ~InSitu();
  InSitu(InSitu&&) noexcept;
  InSitu& operator=(InSitu&&) noexcept;

  // Collective. Describes this step's data; nothing is copied or read yet.
  void publish(long long step, double time, const Published& data);
  // Collective. Renders what the actions ask for if a trigger fires on this step. Errors in the
  // data (NaN) or a failed render are reported and the step's images skipped, unless the actions
  // say on_error: abort (then InSituError is thrown on every rank).
  ExecuteReport execute();

 private:
  struct Impl;
  explicit InSitu(std::unique_ptr<Impl> impl);
  static std::unique_ptr<Impl> open(MPI_Comm comm, const std::string& text, const std::string& source,
                                    bool from_file);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sortlast
