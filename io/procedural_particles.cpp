// Procedural particle sets. Every rank builds the whole set itself, so it must come out
// bit-identical everywhere: randomness is an integer hash of the particle's lattice index, and
// positions use only + - * / and sqrt (correctly rounded in IEEE arithmetic; CMake turns off FMA
// contraction for this file), no trigonometry and no std:: distributions (whose output the
// standard leaves to the library).
//
// Both sets are built in lattice units (neighbouring particles 1 apart), centred on the bounding
// box of the centres and scaled by `spacing` at the end.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "common/error.h"
#include "io/particles.h"

namespace sortlast {

namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64's finaliser: a good 64-bit mix, enough to make lattice indices look random.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
uint64_t hash(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0) {
  return mix(a ^ mix(b ^ mix(c ^ mix(d))));
}
double unit(uint64_t h) { return double(h >> 11) * 0x1.0p-53; }  // [0, 1)
double signedUnit(uint64_t h) { return 2.0 * unit(h) - 1.0; }    // [-1, 1)

// Lattice integers go through uint64_t so negative ones hash too.
uint64_t u64(long long v) { return static_cast<uint64_t>(v); }

// Salts keep the parts' random streams apart.
enum Salt : uint64_t { kPoolOrder = 1, kPoolJitter, kCrownOrder, kCrownJitter, kDroplet };

glm::dvec3 jitter(uint64_t salt, long long i, long long j, long long k, double amount) {
  return amount * glm::dvec3(signedUnit(hash(salt, u64(i), u64(j), u64(k))),
                             signedUnit(hash(salt + 100, u64(i), u64(j), u64(k))),
                             signedUnit(hash(salt + 200, u64(i), u64(j), u64(k))));
}

// cos(K theta) from cos(theta), by the Chebyshev recurrence: the crown's spikes without trig.
double chebyshev(int k, double c) {
  double prev = 1.0, cur = c;
  if (k == 0) return prev;
  for (int n = 1; n < k; ++n) {
    double next = 2.0 * c * cur - prev;
    prev = cur;
    cur = next;
  }
  return cur;
}

struct Candidate {
  glm::dvec3 p;
  double priority;
};

// The n candidates of lowest priority (ties by generation order), kept in generation order. A
// part "grows" in priority order, so its size follows the count it is given.
std::vector<glm::dvec3> lowest(const std::vector<Candidate>& c, size_t n) {
  std::vector<size_t> order(c.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return c[a].priority != c[b].priority ? c[a].priority < c[b].priority : a < b;
  });
  order.resize(std::min(n, order.size()));
  std::sort(order.begin(), order.end());
  std::vector<glm::dvec3> out;
  for (size_t i : order) out.push_back(c[i].p);
  return out;
}

std::vector<glm::dvec3> layers(long long count) {
  constexpr long long kSide = 24;  // the paper's 24 x 24 particles per layer
  std::vector<glm::dvec3> out;
  for (long long n = 0; n < count; ++n)
    out.emplace_back(double(n % kSide), double(n / (kSide * kSide)), double((n / kSide) % kSide));
  return out;
}

// The splash's proportions: 62 % pool, 28 % crown, the rest droplets.
struct SplashShape {
  double pool_radius;  // of the pool's 3 layers, from its particle count
  double crown_radius;
  int spikes;
  double spikeProfile(double cos_theta) const {  // crown height factor, 0.45 .. 1
    double s = std::max(0.0, chebyshev(spikes, cos_theta));
    return 0.45 + 0.55 * s * s * s;
  }
};

// A shallow pool: 3 layers (y = 0, 1, 2), a disc with a ragged edge.
std::vector<glm::dvec3> pool(const SplashShape& s, size_t n) {
  long long r = static_cast<long long>(std::ceil(s.pool_radius)) + 2;
  std::vector<Candidate> c;
  for (long long j = 0; j < 3; ++j)
    for (long long k = -r; k <= r; ++k)
      for (long long i = -r; i <= r; ++i) {
        double radial = std::sqrt(double(i * i + k * k));
        c.push_back(
            {glm::dvec3(double(i), double(j), double(k)) + jitter(kPoolJitter, i, j, k, 0.15),
             radial + 0.8 * unit(hash(kPoolOrder, u64(i), u64(j), u64(k)))});
      }
  return lowest(c, n);
}

// A crown: a ring wall about 2 particles thick standing on the pool (from y = 3), flaring
// outward as it rises, growing highest at `spikes` evenly spaced angles. Returns the height of its
// top (levels above the pool) through `top`.
std::vector<glm::dvec3> crown(const SplashShape& s, size_t n, double& top) {
  long long r = static_cast<long long>(std::ceil(s.crown_radius)) + 1;
  std::vector<glm::ivec2> ring;
  for (long long k = -r; k <= r; ++k)
    for (long long i = -r; i <= r; ++i)
      if (std::abs(std::sqrt(double(i * i + k * k)) - s.crown_radius) <= 1.0)
        ring.emplace_back(int(i), int(k));
  // Enough levels that even the lowest profile (0.45) holds its share of n.
  long long levels =
      static_cast<long long>(std::ceil(double(n) / (0.45 * double(ring.size())))) + 2;
  std::vector<Candidate> c;
  for (long long j = 0; j < levels; ++j)
    for (const glm::ivec2& q : ring) {
      double radial = std::sqrt(double(q.x * q.x + q.y * q.y));
      double flare = (radial + 0.15 * double(j)) / radial;
      glm::dvec3 p(q.x * flare, 3.0 + double(j), q.y * flare);
      double order = (double(j) + 0.5 * unit(hash(kCrownOrder, u64(q.x), u64(j), u64(q.y))));
      c.push_back(
          {p + jitter(kCrownJitter, q.x, j, q.y, 0.15), order / s.spikeProfile(q.x / radial)});
    }
  std::vector<glm::dvec3> out = lowest(c, n);
  top = 0.0;
  for (const glm::dvec3& p : out) top = std::max(top, p.y - 3.0);
  return out;
}

// Acceptance weight of a droplet direction: 1 at a spike, falling to 0 between spikes.
double nearSpike(const SplashShape& s, double cos_theta) {
  double c = std::max(0.0, chebyshev(s.spikes, cos_theta));
  return (c * c) * (c * c);
}

// Droplets: little clusters of 1-5 particles (1 apart) on ballistic arcs leaving the spike tips
// outward, most still near the tips.
std::vector<glm::dvec3> droplets(const SplashShape& s, size_t n, double crown_top) {
  double h = std::max(crown_top, 2.0);
  std::vector<glm::dvec3> out;
  uint64_t attempt = 0;
  for (uint64_t d = 0; out.size() < n; ++d) {
    // An outward direction, drawn by rejection so most droplets leave near a spike.
    double u, v, len2;
    do {
      ++attempt;
      u = signedUnit(hash(kDroplet, attempt, 1));
      v = signedUnit(hash(kDroplet, attempt, 2));
      len2 = u * u + v * v;
    } while (len2 > 1.0 || len2 < 0.04 ||
             unit(hash(kDroplet, attempt, 3)) >= nearSpike(s, u / std::sqrt(len2)));
    double len = std::sqrt(len2);
    glm::dvec2 dir(u / len, v / len);
    double t = unit(hash(kDroplet, d, 4));  // how far along its flight
    t *= t;
    double radial = s.crown_radius + 0.15 * h + t * (0.6 * h + 2.0);
    double y = 3.0 + h + (0.5 * h + 2.0) * (1.6 * t - 1.2 * t * t);
    glm::dvec3 centre(dir.x * radial, y, dir.y * radial);
    static const glm::dvec3 kCluster[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}};
    size_t size = 1 + hash(kDroplet, d, 5) % 5;
    for (size_t m = 0; m < size && out.size() < n; ++m)
      out.push_back(centre + 0.9 * kCluster[m] +
                    jitter(kDroplet, static_cast<long long>(d), static_cast<long long>(m), 6, 0.1));
  }
  return out;
}

std::vector<glm::dvec3> splash(long long count) {
  size_t n = size_t(count), n_pool = n * 62 / 100, n_crown = n * 28 / 100;
  size_t n_drop = n - n_pool - n_crown;
  SplashShape s;
  s.pool_radius = std::sqrt(std::ceil(double(n_pool) / 3.0) / kPi);
  s.crown_radius = std::max(2.0, 0.65 * s.pool_radius);
  s.spikes = std::clamp(int(std::lround(2.0 * kPi * s.crown_radius / 6.0)), 5, 24);
  double top = 0.0;
  std::vector<glm::dvec3> out = pool(s, n_pool);
  std::vector<glm::dvec3> rim = crown(s, n_crown, top);
  std::vector<glm::dvec3> drops = droplets(s, n_drop, top);
  out.insert(out.end(), rim.begin(), rim.end());
  out.insert(out.end(), drops.begin(), drops.end());
  return out;
}

}  // namespace

ParticleSet proceduralParticles(const std::string& name, long long count, double spacing) {
  if (count < 0)
    throw InputError("particles.count: must be >= 0 for a procedural set, got " +
                     std::to_string(count));
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw InputError("particles.spacing: must be a finite number > 0");
  std::vector<glm::dvec3> lattice;
  if (name == "layers")
    lattice = layers(count);
  else if (name == "splash")
    lattice = splash(count);
  else if (name != "none")
    throw InputError("particles.procedural: unknown set '" + name +
                     "' (known: none, layers, splash)");

  // Centre the centres' bounding box on the origin.
  constexpr double inf = std::numeric_limits<double>::infinity();
  glm::dvec3 lo(inf), hi(-inf);
  for (const glm::dvec3& p : lattice) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::dvec3 centre = 0.5 * (lo + hi);
  ParticleSet set;
  set.positions.reserve(lattice.size());
  for (const glm::dvec3& p : lattice) set.positions.push_back(glm::vec3((p - centre) * spacing));
  return set;
}

}  // namespace sortlast
