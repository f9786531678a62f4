// particles: a block of particles dropped into a pool (particle_sim.h), distributed by slabs along
// x and rendered in situ by sortlast as metaballs: every rank publishes its particles' x, y, z
// arrays where they lie, every --every steps. Prints one line per step (see example_cli.h).
//
//   mpirun -np 4 particles --particles 8000 --steps 400 --every 20 --out splash
#include <mpi.h>
#include <sortlast/insitu.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../common/example_cli.h"
#include "particle_sim.h"

namespace {

struct Options {
  ParticleParams sim;
  long long steps = 400, every = 20, dump_step = -1;
  int width = 512;
  std::string out = "particles_out", actions, dump;
  bool print_actions = false, help = false;
};

const char* kUsage =
    "usage: particles [--particles N] [--steps S] [--every K] [--out DIR] [--width W] [--actions "
    "FILE]\n"
    "                 [--dump-step T --dump FILE] [--print-actions]\n"
    "  --particles N   particles in all (default 8000); spacing 1, so particles.radius 0.6\n"
    "  --steps S       steps after the initial state (default 400); step 0 is the initial state\n"
    "  --every K       built-in actions: an image every K steps, DIR/p_{step}.png (default 20)\n"
    "  --width W       built-in actions: image W x W (default 512)\n"
    "  --actions FILE  an actions file instead of the built-in actions (--every, --width, --out "
    "unused)\n"
    "  --dump-step T --dump FILE  all particles at step T on rank 0, raw float32 x,y,z, rank "
    "order\n"
    "  --print-actions print the built-in actions and exit\n";

Options parse(int argc, char** argv) {
  Options o;
  example::ArgReader a(argc, argv);
  while (!a.done()) {
    if (a.value("--particles", o.sim.count) || a.value("--steps", o.steps) ||
        a.value("--every", o.every) || a.value("--out", o.out) || a.value("--width", o.width) ||
        a.value("--actions", o.actions) || a.value("--dump-step", o.dump_step) ||
        a.value("--dump", o.dump) || a.flag("--print-actions", o.print_actions) ||
        a.flag("--help", o.help) || a.flag("-h", o.help))
      continue;
    a.unknown();
  }
  if (o.steps < 0 || o.every < 1 || o.width < 1)
    throw std::invalid_argument("need --steps >= 0, --every >= 1, --width >= 1");
  if (o.dump.empty() != (o.dump_step < 0))
    throw std::invalid_argument("--dump-step and --dump go together");
  return o;
}

// The built-in actions: metaballs of radius 0.6 spacings (smooth enough to read as a liquid, small
// enough that a lone drop shows), water-blue on a dark background, seen from above a corner of the
// box with the whole drop in view. The camera is fixed in the simulation's coordinates, so the
// image series does not jump.
std::string builtinActions(const Options& o, const ParticleSim& sim) {
  const double* b = sim.box();
  const double cx = 0.5 * b[0], cy = 0.42 * sim.dropTop(), cz = 0.5 * b[2];
  const double d = 2.7 * std::max(b[0], sim.dropTop());
  char text[2048];
  const int n =
      std::snprintf(text, sizeof text,
                    "renders:\n"
                    "  - name: particles\n"
                    "    output: %s\n"
                    "    trigger: {every: %lld}\n"
                    "    scene:\n"
                    "      image: {width: %d, height: %d, background: [0.06, 0.07, 0.1]}\n"
                    "      camera: {look_at: [%g, %g, %g], position: [%g, %g, %g], fov: 30}\n"
                    "      particles: {radius: 0.6, color: [0.45, 0.7, 1.0]}\n",
                    example::yamlQuoted(o.out + "/p_{step}.png").c_str(), o.every, o.width, o.width,
                    cx, cy, cz, cx + 0.55 * d, cy + 0.5 * d, cz + 0.8 * d);
  if (n >= int(sizeof text)) throw std::invalid_argument("--out is too long");
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = 0;
  try {
    const Options o = parse(argc, argv);
    if (o.help) {
      if (rank == 0) std::fputs(kUsage, stdout);
      MPI_Finalize();
      return 0;
    }
    ParticleSim sim(o.sim, MPI_COMM_WORLD);
    if (o.print_actions) {
      if (rank == 0) std::fputs(builtinActions(o, sim).c_str(), stdout);
      MPI_Finalize();
      return 0;
    }
    sortlast::InSitu vis = example::openInSitu(MPI_COMM_WORLD, o.actions, builtinActions(o, sim));
    for (long long step = 0; step <= o.steps; ++step) {
      double sim_s = 0;
      if (step > 0) {
        const double t0 = MPI_Wtime();
        sim.step();
        sim_s = MPI_Wtime() - t0;
      }
      sortlast::Published data;
      data.particles.x = sim.x().data();
      data.particles.y = sim.y().data();
      data.particles.z = sim.z().data();
      data.particles.count = sim.count();
      vis.publish(step, double(step) * o.sim.dt, data);
      const sortlast::ExecuteReport report = vis.execute();
      example::printStep(rank, step, sim_s, report);
      if (step == o.dump_step) {
        std::vector<float> all = sim.gather();
        if (rank == 0) example::writeRaw(o.dump, all);
      }
    }
  } catch (const sortlast::InSituError& e) {  // thrown on every rank alike
    if (rank == 0) std::fprintf(stderr, "particles: %s\n", e.what());
    status = 1;
  } catch (const std::invalid_argument& e) {  // options and sizes: every rank decides alike
    if (rank == 0) std::fprintf(stderr, "particles: %s\n%s", e.what(), kUsage);
    status = 2;
  } catch (const std::exception& e) {  // one rank alone (a file it cannot write): stop them all
    std::fprintf(stderr, "particles rank %d: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
