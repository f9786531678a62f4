/* sortlast in situ, C interface (over the C++ API of sortlast/insitu.h; see docs/insitu.md).
 *
 *   sortlast_insitu* vis = sortlast_insitu_open(comm, "actions.yaml");  // collective
 *   if (!vis) { fprintf(stderr, "%s\n", sortlast_insitu_last_error()); ... }
 *   for (long long step = 0; ...; ++step) {
 *     simulate(...);
 *     sortlast_insitu_publish_grid(vis, v, SORTLAST_FLOAT64, dims, NULL, ghost, ghost,
 *                                  origin, spacing);
 *     sortlast_insitu_set_quantity(vis, "energy", energy);
 *     if (sortlast_insitu_execute(vis, step, time) < 0) ...;       // collective
 *   }
 *   sortlast_insitu_close(vis);                                       // collective
 *
 * The publish_* and set_quantity calls describe this rank's data for the next execute; execute
 * hands all of it to sortlast as one step (the C++ publish() and execute()) and forgets it, so each
 * step describes its data again. Nothing is copied: the arrays must stay valid and unchanged until
 * execute returns. A rank with no data of its own publishes nothing but still calls execute.
 *
 * No C++ exception leaves these functions. Functions returning int give 0 on success and -1 on
 * an error; sortlast_insitu_last_error() then says why. The library never calls MPI_Init or
 * MPI_Finalize: open after MPI_Init, close before MPI_Finalize.
 *
 * Fortran: every function can be called through ISO_C_BINDING (bind(C)); the handle is a
 * type(c_ptr), strings end in c_null_char, and the _f variants of open take the communicator as an
 * INTEGER (MPI_Fint). A Fortran array v(nx, ny, nz) is dense with x fastest, as dims = (nx, ny, nz)
 * and strides NULL (c_null_ptr) describe it. */
#ifndef SORTLAST_INSITU_C_H
#define SORTLAST_INSITU_C_H

#include <mpi.h>

#ifdef __cplusplus
extern "C" {
#endif

/* An in-situ session (opaque). */
typedef struct sortlast_insitu sortlast_insitu;

/* Element types of a grid block. */
enum {
  SORTLAST_UINT8 = 0,
  SORTLAST_UINT16 = 1,
  SORTLAST_INT16 = 2,
  SORTLAST_FLOAT32 = 3,
  SORTLAST_FLOAT64 = 4
};

/* Collective over comm. Starts a session that renders what the actions file (YAML) asks for; it
 * uses a duplicate of comm and no other communicator. Returns NULL on every rank if the actions are
 * bad or the session cannot start (sortlast_insitu_last_error() says why). */
sortlast_insitu* sortlast_insitu_open(MPI_Comm comm, const char* actions_file);

/* As sortlast_insitu_open, with the actions as YAML text instead of a file name. */
sortlast_insitu* sortlast_insitu_open_text(MPI_Comm comm, const char* actions_yaml);

/* As sortlast_insitu_open and sortlast_insitu_open_text, with a Fortran communicator handle
 * (MPI_Comm_f2c converts it). */
sortlast_insitu* sortlast_insitu_open_f(MPI_Fint comm, const char* actions_file);
sortlast_insitu* sortlast_insitu_open_text_f(MPI_Fint comm, const char* actions_yaml);

/* The message of the most recent failed call on this thread (also the reason a step was skipped,
 * when execute returned 1); "" if none failed. Valid until the next call on this thread. */
const char* sortlast_insitu_last_error(void);

/* This rank's block of a uniform grid of point samples, for the next execute. Blocks of all ranks
 * tile the global grid without overlapping in their owned samples (any decomposition); a rank with
 * no block does not call this. Arguments:
 *   data       sample (0, 0, 0) of the array, ghost layers included
 *   type       SORTLAST_UINT8 ... SORTLAST_FLOAT64
 *   dims       samples per axis (x, y, z) in the array, ghost layers included
 *   strides    distance in elements between neighbouring samples along x, y, z; NULL: dense, x
 *              fastest (1, dims[0], dims[0] * dims[1])
 *   ghost_lo   ghost layers the array carries before its owned samples on each axis; NULL: none
 *   ghost_hi   ... and after them; NULL: none (sortlast fetches what it needs from neighbours)
 *   origin     world position of the first owned (non-ghost) sample; NULL: (0, 0, 0)
 *   spacing    world distance between samples, the same on every rank; NULL: (1, 1, 1)
 * Calling it again before execute replaces the block. */
int sortlast_insitu_publish_grid(sortlast_insitu* vis, const void* data, int type,
                                 const int dims[3], const long long strides[3],
                                 const int ghost_lo[3], const int ghost_hi[3],
                                 const double origin[3], const double spacing[3]);

/* This rank's particles (metaball centres) for the next execute: particle i is at
 * (x[i * stride], y[i * stride], z[i * stride]), i < count; stride is in doubles (1: separate
 * arrays; 3 with y = x + 1, z = x + 2: interleaved xyz). Calling it again replaces them. */
int sortlast_insitu_publish_particles(sortlast_insitu* vis, const double* x, const double* y,
                                      const double* z, long long stride, long long count);

/* An optional per-particle value named name (values[i * stride], with the stride and count of the
 * particles published for this step) for the next execute. */
int sortlast_insitu_publish_particle_scalar(sortlast_insitu* vis, const char* name,
                                            const double* values);

/* A named quantity for triggers (`trigger: {when: name, crosses: X}` in the actions) for the next
 * execute; the same value on every rank. */
int sortlast_insitu_set_quantity(sortlast_insitu* vis, const char* name, double value);

/* Collective over the session's communicator: every rank calls it once per step, with the same
 * step and time. Hands what was published since the last execute to sortlast as this step and
 * renders what the actions ask for if a trigger fires. Returns 0 if all went well (rendered or not
 * triggered), 1 if this step's images were skipped because of bad data or a failed render (the
 * simulation may go on; sortlast_insitu_last_error() says why), -1 on an error (invalid arguments,
 * or a failed step with `on_error: abort` in the actions, on every rank). */
int sortlast_insitu_execute(sortlast_insitu* vis, long long step, double time);

/* What the last execute did, for the simulation's log. */
typedef struct sortlast_insitu_report {
  int rendered;            /* 1: a trigger fired and images were written */
  int images;              /* files written (on the first rank of the communicator) */
  double seconds;          /* wall time of the execute */
  double memory_added_mib; /* host memory sortlast holds beyond the simulation's (this rank) */
  /* Where this rank renders (truncated to fit, NUL-terminated): GL_VENDOR, GL_RENDERER, host, and
   * the hardware EGL device (-1: software rendering). Filled after the first execute. */
  char gl_vendor[64];
  char gl_renderer[128];
  char host[64];
  int device;
} sortlast_insitu_report;

/* Fills *report with what the last execute did (all zero before the first). */
int sortlast_insitu_last_report(const sortlast_insitu* vis, sortlast_insitu_report* report);

/* The accuracy of the last image the last execute wrote, estimated while it rendered
 * (render.estimate, docs/volumes.md; on the first rank of the communicator): the estimated PSNR
 * against the exact model in dB and its 95 % bounds (HUGE_VAL: no difference seen), the share of
 * pixels more than 4/255 off and its 95 % upper bound. Returns 1 where that image has an estimate,
 * 0 where not (the values are then NaN: particles in the frame, render.estimate: off, another
 * rank, ...), -1 on a NULL session. Any output pointer may be NULL. */
int sortlast_insitu_last_accuracy(const sortlast_insitu* vis, double* psnr_db, double* psnr_db_lo,
                                  double* psnr_db_hi, double* over4_share, double* over4_share_hi);

/* Collective. Ends the session and frees it; NULL is ignored. */
void sortlast_insitu_close(sortlast_insitu* vis);

#ifdef __cplusplus
}
#endif

#endif /* SORTLAST_INSITU_C_H */
