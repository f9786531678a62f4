// The C interface (include/sortlast/insitu_c.h) over sortlast::InSitu: a handle holds the session
// and the step being described; every entry point catches whatever the C++ side throws and turns
// it into a return code and a message.
#include "sortlast/insitu_c.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <utility>

#include "sortlast/insitu.h"

struct sortlast_insitu {
  sortlast::InSitu vis;
  sortlast::Published pending;  // what publish_* / set_quantity described since the last execute
  sortlast::ExecuteReport last;
};

namespace {

thread_local std::string last_error;

int fail(std::string message) {
  last_error = std::move(message);
  return -1;
}

// Runs body (returning int); an exception becomes -1 and the message.
template <typename Body>
int guarded(Body&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return fail("out of memory");
  } catch (const std::exception& e) {
    return fail(e.what());
  } catch (...) {
    return fail("unknown error");
  }
}

template <typename Make>
sortlast_insitu* open_session(Make&& make, const char* what, const char* arg) noexcept {
  sortlast_insitu* vis = nullptr;
  guarded([&] {
    if (arg == nullptr) return fail(std::string("sortlast_insitu_open: ") + what + " is NULL");
    vis = new sortlast_insitu{make(std::string(arg)), {}, {}};
    return 0;
  });
  return vis;
}

bool element_type(int type, sortlast::ElementType* out) {
  switch (type) {
    case SORTLAST_UINT8:
      *out = sortlast::ElementType::kUint8;
      return true;
    case SORTLAST_UINT16:
      *out = sortlast::ElementType::kUint16;
      return true;
    case SORTLAST_INT16:
      *out = sortlast::ElementType::kInt16;
      return true;
    case SORTLAST_FLOAT32:
      *out = sortlast::ElementType::kFloat32;
      return true;
    case SORTLAST_FLOAT64:
      *out = sortlast::ElementType::kFloat64;
      return true;
    default:
      return false;
  }
}

template <typename T, typename U>
void copy3(const T* from, U& to) {
  if (from != nullptr) to = {from[0], from[1], from[2]};
}

}  // namespace

extern "C" {

sortlast_insitu* sortlast_insitu_open(MPI_Comm comm, const char* actions_file) {
  return open_session([&](const std::string& file) { return sortlast::InSitu(comm, file); },
                      "actions_file", actions_file);
}

sortlast_insitu* sortlast_insitu_open_text(MPI_Comm comm, const char* actions_yaml) {
  return open_session(
      [&](const std::string& yaml) { return sortlast::InSitu::fromText(comm, yaml); },
      "actions_yaml", actions_yaml);
}

sortlast_insitu* sortlast_insitu_open_f(MPI_Fint comm, const char* actions_file) {
  return sortlast_insitu_open(MPI_Comm_f2c(comm), actions_file);
}

sortlast_insitu* sortlast_insitu_open_text_f(MPI_Fint comm, const char* actions_yaml) {
  return sortlast_insitu_open_text(MPI_Comm_f2c(comm), actions_yaml);
}

const char* sortlast_insitu_last_error(void) { return last_error.c_str(); }

int sortlast_insitu_publish_grid(sortlast_insitu* vis, const void* data, int type,
                                 const int dims[3], const long long strides[3],
                                 const int ghost_lo[3], const int ghost_hi[3],
                                 const double origin[3], const double spacing[3]) {
  return guarded([&] {
    if (vis == nullptr) return fail("sortlast_insitu_publish_grid: the session is NULL");
    if (dims == nullptr) return fail("sortlast_insitu_publish_grid: dims is NULL");
    sortlast::GridBlock grid;
    if (!element_type(type, &grid.type)) {
      return fail("sortlast_insitu_publish_grid: unknown element type " + std::to_string(type));
    }
    grid.data = data;
    copy3(dims, grid.dims);
    copy3(strides, grid.strides);
    copy3(ghost_lo, grid.ghost_lo);
    copy3(ghost_hi, grid.ghost_hi);
    copy3(origin, grid.origin);
    copy3(spacing, grid.spacing);
    vis->pending.grid = std::move(grid);
    return 0;
  });
}

int sortlast_insitu_publish_particles(sortlast_insitu* vis, const double* x, const double* y,
                                      const double* z, long long stride, long long count) {
  return guarded([&] {
    if (vis == nullptr) return fail("sortlast_insitu_publish_particles: the session is NULL");
    sortlast::ParticleBlock& particles = vis->pending.particles;
    particles.x = x;
    particles.y = y;
    particles.z = z;
    particles.x32 = particles.y32 = particles.z32 = nullptr;
    particles.stride = stride;
    particles.count = count;
    return 0;
  });
}

int sortlast_insitu_publish_particle_scalar(sortlast_insitu* vis, const char* name,
                                            const double* values) {
  return guarded([&] {
    if (vis == nullptr) return fail("sortlast_insitu_publish_particle_scalar: the session is NULL");
    if (name == nullptr) return fail("sortlast_insitu_publish_particle_scalar: name is NULL");
    vis->pending.particles.scalars[name] = values;
    return 0;
  });
}

int sortlast_insitu_set_quantity(sortlast_insitu* vis, const char* name, double value) {
  return guarded([&] {
    if (vis == nullptr) return fail("sortlast_insitu_set_quantity: the session is NULL");
    if (name == nullptr) return fail("sortlast_insitu_set_quantity: name is NULL");
    vis->pending.quantities[name] = value;
    return 0;
  });
}

int sortlast_insitu_execute(sortlast_insitu* vis, long long step, double time) {
  if (vis == nullptr) return fail("sortlast_insitu_execute: the session is NULL");
  // The step's description is gone after this call, whatever happens.
  sortlast::Published data = std::exchange(vis->pending, {});
  vis->last = {};
  return guarded([&] {
    vis->vis.publish(step, time, data);
    vis->last = vis->vis.execute();
    if (!vis->last.error.empty()) {
      last_error = vis->last.error;
      return 1;
    }
    return 0;
  });
}

int sortlast_insitu_last_report(const sortlast_insitu* vis, sortlast_insitu_report* report) {
  if (vis == nullptr || report == nullptr) {
    return fail("sortlast_insitu_last_report: the session or the report is NULL");
  }
  report->rendered = vis->last.rendered ? 1 : 0;
  report->images = static_cast<int>(vis->last.images.size());
  report->seconds = vis->last.seconds;
  report->memory_added_mib = vis->last.memory_added_mib;
  auto copy = [](char* to, size_t n, const std::string& from) {
    std::snprintf(to, n, "%s", from.c_str());
  };
  copy(report->gl_vendor, sizeof report->gl_vendor, vis->last.gl_vendor);
  copy(report->gl_renderer, sizeof report->gl_renderer, vis->last.gl_renderer);
  copy(report->host, sizeof report->host, vis->last.host);
  report->device = vis->last.device;
  return 0;
}

int sortlast_insitu_last_accuracy(const sortlast_insitu* vis, double* psnr_db, double* psnr_db_lo,
                                  double* psnr_db_hi, double* over4_share, double* over4_share_hi) {
  if (vis == nullptr) return fail("sortlast_insitu_last_accuracy: the session is NULL");
  const sortlast::ExecuteReport& r = vis->last;
  auto put = [](double* to, double v) {
    if (to) *to = v;
  };
  put(psnr_db, r.estimated_psnr_db);
  put(psnr_db_lo, r.psnr_db_lo);
  put(psnr_db_hi, r.psnr_db_hi);
  put(over4_share, r.over4_share);
  put(over4_share_hi, r.over4_share_hi);
  return std::isnan(r.estimated_psnr_db) ? 0 : 1;
}

void sortlast_insitu_close(sortlast_insitu* vis) {
  guarded([&] {
    delete vis;
    return 0;
  });
}

}  // extern "C"
