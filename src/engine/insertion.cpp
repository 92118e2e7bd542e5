#include "engine/insertion.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/particle_init.hpp"
#include "scene/counter_random.hpp"
#include "scene/scene_loader.hpp"
#include "scene/sphere_grid.hpp"
#include "walls/sphere_triangle.hpp"

namespace gs {
namespace {

// Streams of the counter generator per inlet: what a particle is (size and
// velocity), and where its candidates go.
constexpr std::uint64_t kParticleStream = 0, kPositionStream = 1;
std::uint64_t stream(std::size_t inlet, std::uint64_t kind) { return (std::uint64_t(inlet) << 8) | kind; }

// Particle `index` of the inlet's sequence: its size and velocity depend on
// the index alone, so a particle owed for several batches stays the same one.
ParticleInit sequence_particle(const InletSpec& in, std::size_t which, std::uint64_t index) {
  auto u = [&](std::uint64_t draw) { return counter_uniform(in.seed, stream(which, kParticleStream), index, draw); };
  ParticleInit p;
  p.material = in.tmpl.material;
  p.marker = in.tmpl.marker;
  p.radius = radius_at(in.size, u(0));
  const double s = in.velocity_spread;
  p.velocity = in.tmpl.velocity + Vec3d(s * (2 * u(1) - 1), s * (2 * u(2) - 1), s * (2 * u(3) - 1));
  p.angular_velocity = in.tmpl.angular_velocity;
  return p;
}

// What the inlet owes in all by time t: its rate over the time since start
// (or the total at once without a rate), never beyond the total.
double amount_due(const InletSpec& in, double t) {
  if (t < in.start) return 0;
  if (in.rate == 0) return in.total;
  const double elapsed = std::min(t, in.stop) - in.start;
  double due = in.rate * elapsed;
  // A count owed is whole: the slack keeps rate * t that rounds to just below an integer from losing a particle.
  if (in.rate_of == InletSpec::Amount::count) due = std::floor(due * (1 + 1e-12));
  if (in.rate_of == in.total_of) due = std::min(due, in.total);
  return due;
}

// Whether the inlet has reached its total (in what the total counts).
bool total_reached(const InletSpec& in, std::uint64_t count, double mass) {
  return in.total_of == InletSpec::Amount::count ? double(count) >= in.total : mass >= in.total;
}

bool clear_of_walls(const Vec3d& c, double r, const std::vector<Wall>& walls) {
  for (const Wall& w : walls)
    if (w.active && wall_penetration(w, c, r) > 0) return false;  // an open gate is no obstacle
  return true;
}

// Triangles whose bounding box comes within `reach` of the box [lo, hi]: the
// only ones a candidate in the box can touch.
std::vector<std::int32_t> triangles_near(const MeshSet& m, const Vec3d& lo, const Vec3d& hi, double reach) {
  std::vector<std::int32_t> near;
  for (std::int32_t t = 0; t < m.n_triangles(); ++t) {
    const MeshCorners& k = m.corners[std::size_t(t)];
    Vec3d a = m.vertex[std::size_t(k.v[0])], b = a;
    for (int c = 1; c < 3; ++c) {
      const Vec3d& v = m.vertex[std::size_t(k.v[c])];
      a = Vec3d(std::min(a.x, v.x), std::min(a.y, v.y), std::min(a.z, v.z));
      b = Vec3d(std::max(b.x, v.x), std::max(b.y, v.y), std::max(b.z, v.z));
    }
    if (a.x <= hi.x + reach && b.x >= lo.x - reach && a.y <= hi.y + reach && b.y >= lo.y - reach &&
        a.z <= hi.z + reach && b.z >= lo.z - reach)
      near.push_back(t);
  }
  return near;
}

bool clear_of_meshes(const Vec3d& c, double r, const MeshSet& m, const std::vector<std::int32_t>& near) {
  for (std::int32_t t : near) {
    const MeshCorners& k = m.corners[std::size_t(t)];
    const ClosestPoint q = closest_point_on_triangle(c, m.vertex[std::size_t(k.v[0])], m.vertex[std::size_t(k.v[1])],
                                                     m.vertex[std::size_t(k.v[2])]);
    if (q.distance < r) return false;
  }
  return true;
}

}  // namespace

InsertionState initial_insertion_state(std::size_t inlets, std::size_t scene_particles) {
  InsertionState s;
  s.next_id = scene_particles;
  s.inlets.assign(inlets, InletState{});
  return s;
}

bool batch_due(const InletSpec& inlet, long long step) { return step > 0 && step % inlet.interval_steps == 0; }

InletBatch inlet_batch(const InletSpec& in, std::size_t which, const InletState& state, double t,
                       const std::vector<MaterialSpec>& materials) {
  InletBatch b;
  b.attempts = in.attempts;
  const double due = amount_due(in, t);
  const MaterialSpec& material = materials[std::size_t(in.tmpl.material)];
  std::uint64_t count = state.inserted;
  double mass = state.mass;
  // A count is owed particle by particle; a mass until the particles owed
  // reach it. `due` counts what the rate counts, or the total without a rate.
  const InletSpec::Amount due_of = in.rate > 0 ? in.rate_of : in.total_of;
  auto owes = [&] {
    if (total_reached(in, count, mass)) return false;
    return due_of == InletSpec::Amount::count ? double(count) < due : mass < due;
  };
  while (owes()) {
    const ParticleInit p = sequence_particle(in, which, count);
    const float m = stored_mass(p.radius, material);
    b.pending.push_back(p);
    b.mass.push_back(m);
    mass += double(m);
    ++count;
  }
  b.candidates.reserve(b.pending.size() * std::size_t(in.attempts));
  for (std::size_t k = 0; k < b.pending.size(); ++k) {
    const std::uint64_t index = state.inserted + k;
    const FillRegion centres = shrunk(in.region, b.pending[k].radius);
    for (int a = 0; a < in.attempts; ++a) {
      const std::uint64_t draw = 3 * (state.batches * std::uint64_t(in.attempts) + std::uint64_t(a));
      auto u = [&](std::uint64_t d) { return counter_uniform(in.seed, stream(which, kPositionStream), index, draw + d); };
      b.candidates.push_back(region_point(centres, Vec3d(u(0), u(1), u(2))));
    }
  }
  return b;
}

namespace {

// The shifts by whole box lengths that give a sphere's images: each wrapping
// axis by -L, 0 or +L (all nine of a chute periodic in x and y), the zero
// shift first; only the zero shift when nothing wraps.
std::vector<Vec3d> image_shifts(const PeriodicBox& box) {
  std::vector<Vec3d> shifts{Vec3d()};
  for (int axis = 0; axis < 3; ++axis) {
    if (!box.wraps(axis)) continue;
    const double l = component(box.length, axis);
    const std::size_t n = shifts.size();
    for (int sign : {-1, 1})
      for (std::size_t k = 0; k < n; ++k) {
        Vec3d s = shifts[k];
        (axis == 0 ? s.x : axis == 1 ? s.y : s.z) = sign * l;
        shifts.push_back(s);
      }
  }
  return shifts;
}

// f(image) for each periodic image (centre + shift) that comes within `reach`
// of the box [lo, hi]: the ones that can touch a sphere centred in it.
template <class F>
void for_each_image_near(const std::vector<Vec3d>& shifts, const Vec3d& centre, double reach, const Vec3d& lo,
                         const Vec3d& hi, F&& f) {
  for (const Vec3d& shift : shifts) {
    const Vec3d c = centre + shift;
    if (c.x + reach > lo.x && c.x - reach < hi.x && c.y + reach > lo.y && c.y - reach < hi.y &&
        c.z + reach > lo.z && c.z - reach < hi.z)
      f(c);
  }
}

}  // namespace

void mark_blocked(const InletBatch& b, const std::vector<Vec3d>& centre, const std::vector<float>& radius,
                  const PeriodicBox& box, std::vector<double>& blocked) {
  blocked.resize(b.candidates.size(), 0.0);
  if (b.candidates.empty() || centre.empty()) return;
  // Only spheres that can reach a candidate matter: those near the candidates' box.
  Vec3d lo = b.candidates.front(), hi = lo;
  double r_max = 0, r_sum = 0;
  for (const Vec3d& c : b.candidates) {
    lo = Vec3d(std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z));
    hi = Vec3d(std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z));
  }
  for (const ParticleInit& p : b.pending) {
    r_max = std::max(r_max, p.radius);
    r_sum += p.radius;
  }
  // A sphere near a periodic face reaches candidates near the other face
  // through its image: each image is tested as a sphere of its own. The
  // images are the same on every rank, so the marks stay rank-independent.
  const std::vector<Vec3d> shifts = image_shifts(box);
  std::vector<std::pair<Vec3d, double>> near;
  double reach = 0;
  for (std::size_t i = 0; i < centre.size(); ++i)
    for_each_image_near(shifts, centre[i], double(radius[i]) + r_max, lo, hi, [&](const Vec3d& c) {
      near.emplace_back(c, double(radius[i]));
      reach = std::max(reach, double(radius[i]));
    });
  if (near.empty()) return;
  const Vec3d pad(reach + r_max, reach + r_max, reach + r_max);
  SphereGrid grid(lo - pad, hi + pad, 2 * r_sum / double(b.pending.size()), near.size());
  for (const auto& [c, r] : near) grid.insert(c, r);
  for (std::size_t k = 0; k < b.pending.size(); ++k)
    for (int a = 0; a < b.attempts; ++a) {
      const std::size_t c = k * std::size_t(b.attempts) + std::size_t(a);
      if (grid.overlapping(b.candidates[c], b.pending[k].radius, 0.0) >= 0) blocked[c] += 1;
    }
}

std::vector<ParticleInit> accept_candidates(const InletBatch& b, const std::vector<double>& blocked,
                                            const std::vector<Wall>& walls, const MeshSet& meshes) {
  std::vector<ParticleInit> accepted;
  if (b.pending.empty()) return accepted;
  Vec3d lo = b.candidates.front(), hi = lo;
  double r_max = 0;
  for (const Vec3d& c : b.candidates) {
    lo = Vec3d(std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z));
    hi = Vec3d(std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z));
  }
  for (const ParticleInit& p : b.pending) r_max = std::max(r_max, p.radius);
  const Vec3d pad(r_max, r_max, r_max);
  SphereGrid batch(lo - pad, hi + pad, 2 * r_max, b.pending.size());
  const std::vector<std::int32_t> near = triangles_near(meshes, lo, hi, r_max);
  for (std::size_t k = 0; k < b.pending.size(); ++k) {
    const double r = b.pending[k].radius;
    bool placed = false;
    for (int a = 0; a < b.attempts && !placed; ++a) {
      const std::size_t c = k * std::size_t(b.attempts) + std::size_t(a);
      const Vec3d& x = b.candidates[c];
      if (blocked[c] > 0 || batch.overlapping(x, r, 0.0) >= 0 || !clear_of_walls(x, r, walls) ||
          !clear_of_meshes(x, r, meshes, near))
        continue;
      ParticleInit p = b.pending[k];
      p.position = x;
      accepted.push_back(p);
      batch.insert(x, r);
      placed = true;
    }
    if (!placed) break;
  }
  return accepted;
}

}  // namespace gs
