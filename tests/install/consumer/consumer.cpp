// Each rank publishes an 8x8x8 float block (slabs along z: rank r holds z = 8r ... 8r + 7) of a
// ball centred in the global grid, and executes step 1 once with the actions file argv[1].
// Also checks that a bad actions file throws sortlast::InSituError across the library boundary.
#include <mpi.h>
#include <sortlast/insitu.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int status = 0;
  auto fail = [&](const char* what, const char* why) {
    std::fprintf(stderr, "consumer_cxx rank %d: %s: %s\n", rank, what, why);
    status = 1;
  };

  try {
    sortlast::InSitu bad(MPI_COMM_WORLD, "/nonexistent/actions.yaml");
    fail("missing actions file", "no InSituError");
  } catch (const sortlast::InSituError&) {
  }

  const int n = 8;
  const double cz = 0.5 * (n * size - 1), radius = 0.5 * n * size;
  std::vector<float> v(n * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        double d = std::hypot(x - 3.5, y - 3.5, rank * n + z - cz) / radius;
        v[(z * n + y) * n + x] = static_cast<float>(std::max(0.0, 1.0 - d));
      }
  try {
    sortlast::InSitu vis(MPI_COMM_WORLD, argc > 1 ? argv[1] : "actions.yaml");
    sortlast::Published data;
    data.grid.data = v.data();
    data.grid.type = sortlast::ElementType::kFloat32;
    data.grid.dims = {n, n, n};
    data.grid.origin = {0.0, 0.0, double(rank * n)};
    vis.publish(1, 0.5, data);
    sortlast::ExecuteReport report = vis.execute();
    if (!report.error.empty()) fail("execute", report.error.c_str());
    if (rank == 0 && (!report.rendered || report.images.empty())) fail("execute", "no image");
    if (rank == 0) {
      for (const auto& image : report.images) std::printf("consumer_cxx wrote %s\n", image.c_str());
    }
  } catch (const sortlast::InSituError& e) {
    fail("InSituError", e.what());
  }
  MPI_Finalize();
  return status;
}
