// gray_scott: a 3D Gray-Scott reaction-diffusion (gray_scott.h) rendered in situ by sortlast: every
// rank publishes its block of V where it lies (float64, with its ghost layers) and sortlast draws
// the volume every --every steps. Prints one line per step (see example_cli.h).
//
//   mpirun -np 4 gray_scott --size 64 --steps 2000 --every 20 --out gs
#include <mpi.h>
#include <sortlast/insitu.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../common/example_cli.h"
#include "gray_scott.h"

namespace {

struct Options {
  GrayScottParams sim;
  long long steps = 2000, every = 20, dump_step = -1;
  int width = 512;
  std::string out = "gray_scott_out", actions, dump;
  bool float32 = false, no_ghosts = false, print_actions = false, help = false;
};

const char* kUsage =
    "usage: gray_scott [--size N] [--steps S] [--every K] [--out DIR] [--width W] [--actions "
    "FILE]\n"
    "                  [--dump-step T --dump FILE] [--float32] [--no-ghosts] [--print-actions] "
    "[--F F --k K]\n"
    "  --size N        global grid N^3 (default 64), periodic, on MPI_Dims_create's rank grid\n"
    "  --F F, --k K    feed and kill rates (default 0.022, 0.051)\n"
    "  --steps S       steps after the initial state (default 2000); step 0 is the initial state\n"
    "  --every K       built-in actions: an image every K steps, DIR/v_{step}.png (default 20)\n"
    "  --width W       built-in actions: image W x W (default 512)\n"
    "  --actions FILE  an actions file instead of the built-in actions (--every, --width, --out "
    "unused)\n"
    "  --dump-step T --dump FILE  V at step T, gathered to rank 0, raw float32, x fastest\n"
    "  --float32       publish a float32 copy of V instead of the float64 array\n"
    "  --no-ghosts     publish only the owned samples (strides into the array, no ghost layers)\n"
    "  --print-actions print the built-in actions and exit\n";

Options parse(int argc, char** argv) {
  Options o;
  example::ArgReader a(argc, argv);
  while (!a.done()) {
    if (a.value("--size", o.sim.n) || a.value("--F", o.sim.F) || a.value("--k", o.sim.k) ||
        a.value("--steps", o.steps) || a.value("--every", o.every) || a.value("--out", o.out) ||
        a.value("--width", o.width) || a.value("--actions", o.actions) ||
        a.value("--dump-step", o.dump_step) || a.value("--dump", o.dump) ||
        a.flag("--float32", o.float32) || a.flag("--no-ghosts", o.no_ghosts) ||
        a.flag("--print-actions", o.print_actions) || a.flag("--help", o.help) ||
        a.flag("-h", o.help))
      continue;
    a.unknown();
  }
  if (o.sim.n < 2 || o.steps < 0 || o.every < 1 || o.width < 1)
    throw std::invalid_argument("need --size >= 2, --steps >= 0, --every >= 1, --width >= 1");
  if (o.dump.empty() != (o.dump_step < 0))
    throw std::invalid_argument("--dump-step and --dump go together");
  return o;
}

// The built-in actions: V as a volume seen from above a corner of the domain. The camera is in the
// simulation's coordinates (the grid spans 0 ... N-1 on every axis). V stays below 0.5, so the
// transfer function maps a fixed [0, 0.5] (the same colours on every step): a faint blue where V
// is low, the sheets of the reaction front orange to white. The sheets are 2-3 samples thick, so
// rays are sampled every half sample: at 1 they alias into wood-grain stripes.
std::string builtinActions(const Options& o) {
  const double c = 0.5 * (o.sim.n - 1), d = 3.5 * o.sim.n;
  char text[2048];
  const int n =
      std::snprintf(text, sizeof text,
                    "renders:\n"
                    "  - name: v\n"
                    "    output: %s\n"
                    "    trigger: {every: %lld}\n"
                    "    scene:\n"
                    "      image: {width: %d, height: %d}\n"
                    "      camera: {look_at: [%g, %g, %g], position: [%g, %g, %g], fov: 30}\n"
                    "      render: {sample_spacing: 0.5}\n"
                    "      transfer:\n"
                    "        range: [0, 0.5]\n"
                    "        points:\n"
                    "          - [0, 0, 0, 0, 0]\n"
                    "          - [0.25, 0.05, 0.1, 0.4, 0]\n"
                    "          - [0.42, 0.15, 0.35, 0.85, 0.02]\n"
                    "          - [0.55, 0.95, 0.55, 0.2, 0.12]\n"
                    "          - [0.68, 1, 0.8, 0.45, 0.4]\n"
                    "          - [0.85, 1, 1, 0.9, 0.7]\n"
                    "          - [1, 1, 1, 1, 0.85]\n",
                    example::yamlQuoted(o.out + "/v_{step}.png").c_str(), o.every, o.width, o.width,
                    c, c, c, c + 0.5 * d, c + 0.45 * d, c + 0.74 * d);
  if (n >= int(sizeof text)) throw std::invalid_argument("--out is too long");
  return text;
}

// V where it lies: the whole array with its ghost layers, or (--no-ghosts) only the owned samples,
// the pointer at the first of them and the strides of the whole array. --float32: `copy` is
// refreshed from V and described instead, with the same layout.
sortlast::Published describeV(const GrayScott& sim, const Options& o, std::vector<float>& copy) {
  const std::vector<double>& v = sim.v();
  if (o.float32) copy.assign(v.begin(), v.end());
  const auto own = sim.owned();
  const auto off = sim.offset();
  sortlast::Published data;
  sortlast::GridBlock& g = data.grid;
  g.name = "V";
  g.type = o.float32 ? sortlast::ElementType::kFloat32 : sortlast::ElementType::kFloat64;
  g.origin = {double(off[0]), double(off[1]), double(off[2])};  // spacing 1
  const long long first = o.no_ghosts ? sim.index(1, 1, 1) : 0;
  g.data = o.float32 ? static_cast<const void*>(copy.data() + first)
                     : static_cast<const void*>(v.data() + first);
  if (o.no_ghosts) {
    g.dims = own;
    g.strides = {1, sim.index(0, 1, 0), sim.index(0, 0, 1)};
  } else {
    g.dims = {own[0] + 2, own[1] + 2, own[2] + 2};
    g.ghost_lo = g.ghost_hi = {1, 1, 1};
  }
  return data;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = 0;
  try {
    const Options o = parse(argc, argv);
    if (o.help || o.print_actions) {
      if (rank == 0) std::fputs(o.help ? kUsage : builtinActions(o).c_str(), stdout);
      MPI_Finalize();
      return 0;
    }
    GrayScott sim(o.sim, MPI_COMM_WORLD);
    sortlast::InSitu vis = example::openInSitu(MPI_COMM_WORLD, o.actions, builtinActions(o));
    std::vector<float> copy;  // --float32: V as float, same layout (ghosts included)
    for (long long step = 0; step <= o.steps; ++step) {
      double sim_s = 0;
      if (step > 0) {
        const double t0 = MPI_Wtime();
        sim.step();
        sim_s = MPI_Wtime() - t0;
      }
      const sortlast::Published data = describeV(sim, o, copy);
      vis.publish(step, double(step) * o.sim.dt, data);
      const sortlast::ExecuteReport report = vis.execute();
      example::printStep(rank, step, sim_s, report);
      if (step == o.dump_step) {
        std::vector<float> all = sim.gatherV();
        if (rank == 0) example::writeRaw(o.dump, all);
      }
    }
  } catch (const sortlast::InSituError& e) {  // thrown on every rank alike
    if (rank == 0) std::fprintf(stderr, "gray_scott: %s\n", e.what());
    status = 1;
  } catch (const std::invalid_argument& e) {  // options: every rank parses the same argv
    if (rank == 0) std::fprintf(stderr, "gray_scott: %s\n%s", e.what(), kUsage);
    status = 2;
  } catch (const std::exception& e) {  // one rank alone (a file it cannot write): stop them all
    std::fprintf(stderr, "gray_scott rank %d: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
