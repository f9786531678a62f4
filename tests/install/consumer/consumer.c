/* The C interface: each rank publishes an 8x8x8 float block (slabs along z: rank r holds
 * z = 8r ... 8r + 7) of a ball centred in the global grid, and executes step 1 once with the
 * actions file argv[1]. Also checks the error paths (NULL session, bad element type) and the
 * Fortran-handle open. */
#include <mpi.h>
#include <sortlast/insitu_c.h>
#include <stdio.h>
#include <string.h>

static int status = 0;
static int rank = 0;

static void fail(const char* what) {
  fprintf(stderr, "consumer_c rank %d: %s: %s\n", rank, what, sortlast_insitu_last_error());
  status = 1;
}

int main(int argc, char** argv) {
  enum { n = 8 };
  static float v[n * n * n];
  int size = 1;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  /* A missing actions file: NULL and a message, through the Fortran-handle variant. */
  if (sortlast_insitu_open_f(MPI_Comm_c2f(MPI_COMM_WORLD), "/nonexistent/actions.yaml") != NULL ||
      sortlast_insitu_last_error()[0] == '\0') {
    fail("missing actions file");
  }

  double cz = 0.5 * (n * size - 1), radius = 0.5 * n * size;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        double dz = rank * n + z - cz;
        double d2 = ((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) + dz * dz) / (radius * radius);
        v[(z * n + y) * n + x] = (float)(d2 < 1 ? 1 - d2 : 0);
      }

  sortlast_insitu* vis = sortlast_insitu_open(MPI_COMM_WORLD, argc > 1 ? argv[1] : "actions.yaml");
  if (vis == NULL) {
    fail("open");
    MPI_Finalize();
    return 1;
  }
  const int dims[3] = {n, n, n};
  const double origin[3] = {0, 0, rank * n};
  const double spacing[3] = {1, 1, 1};
  if (sortlast_insitu_publish_grid(NULL, v, SORTLAST_FLOAT32, dims, NULL, NULL, NULL, origin,
                                   spacing) != -1) {
    fail("publish_grid accepted a NULL session");
  }
  if (sortlast_insitu_publish_grid(vis, v, 99, dims, NULL, NULL, NULL, origin, spacing) != -1 ||
      strstr(sortlast_insitu_last_error(), "99") == NULL) {
    fail("publish_grid accepted element type 99");
  }
  if (sortlast_insitu_publish_grid(vis, v, SORTLAST_FLOAT32, dims, NULL, NULL, NULL, origin,
                                   spacing) != 0) {
    fail("publish_grid");
  }
  if (sortlast_insitu_set_quantity(vis, "energy", 1.0) != 0) fail("set_quantity");
  int rc = sortlast_insitu_execute(vis, 1, 0.5);
  if (rc != 0) fail("execute");
  sortlast_insitu_report report;
  if (sortlast_insitu_last_report(vis, &report) != 0) fail("last_report");
  if (rank == 0 && (!report.rendered || report.images < 1)) fail("execute wrote no image");
  if (rank == 0) printf("consumer_c: %d image(s) in %.3f s\n", report.images, report.seconds);
  sortlast_insitu_close(vis);
  MPI_Finalize();
  return status;
}
