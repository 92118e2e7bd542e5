#include "analysis/bin_average.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <limits>

namespace gs {
namespace {

constexpr double kPi = 3.14159265358979323846;

long long axis_bin(double x, double lo, double hi, int n) {
  if (!(x >= lo && x <= hi)) return -1;
  const long long k = static_cast<long long>(std::floor((x - lo) / (hi - lo) * n));
  return k < n ? k : n - 1;
}

double bin_volume(const AverageSpec& a) {
  const Vec3d size = a.max - a.min;
  return size.x / a.bins[0] * (size.y / a.bins[1]) * (size.z / a.bins[2]);
}

}  // namespace

long long bin_of(const AverageSpec& a, const Vec3d& x) {
  const long long ix = axis_bin(x.x, a.min.x, a.max.x, a.bins[0]);
  const long long iy = axis_bin(x.y, a.min.y, a.max.y, a.bins[1]);
  const long long iz = axis_bin(x.z, a.min.z, a.max.z, a.bins[2]);
  if (ix < 0 || iy < 0 || iz < 0) return -1;
  return ix + a.bins[0] * (iy + a.bins[1] * iz);
}

std::vector<BinAverage> bin_averages(const AverageSpec& spec, const ParticleSnapshot& s,
                                     const std::vector<ContactMeasure>& contacts) {
  std::vector<BinAverage> bins(std::size_t(spec.bin_count()));
  std::vector<long long> bin(s.size());
  std::vector<Vec3d> momentum(bins.size());
  std::vector<double> solid(bins.size());
  std::vector<long long> contact_count(bins.size());
  const bool with_contacts = contacts.size() == s.size();
  // First pass: mass, momentum, sphere volume, contacts.
  for (std::size_t i = 0; i < s.size(); ++i) {
    bin[i] = bin_of(spec, s.position[i]);
    if (bin[i] < 0) continue;
    const std::size_t b = std::size_t(bin[i]);
    const double m = double(s.mass[i]), r = double(s.radius[i]);
    ++bins[b].particles;
    bins[b].mass += m;
    momentum[b] += s.velocity[i] * m;
    solid[b] += 4.0 / 3.0 * kPi * r * r * r;
    if (with_contacts) {
      contact_count[b] += contacts[i].contacts;
      bins[b].contact_stress += contacts[i].stress_moment;
    }
  }
  const double volume = bin_volume(spec);
  for (std::size_t b = 0; b < bins.size(); ++b) {
    BinAverage& a = bins[b];
    a.solid_fraction = solid[b] / volume;
    if (a.mass > 0) a.velocity = momentum[b] * (1.0 / a.mass);
    a.coordination = a.particles > 0 ? double(contact_count[b]) / double(a.particles)
                                     : std::numeric_limits<double>::quiet_NaN();
  }
  // Second pass: fluctuations about the bin's mean velocity.
  std::vector<double> fluctuation(bins.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (bin[i] < 0) continue;
    const std::size_t b = std::size_t(bin[i]);
    const Vec3d v = s.velocity[i] - bins[b].velocity;
    const double m = double(s.mass[i]);
    fluctuation[b] += m * norm2(v);
    bins[b].kinetic_stress += outer(v * m, v);
  }
  for (std::size_t b = 0; b < bins.size(); ++b) {
    BinAverage& a = bins[b];
    if (a.mass > 0) a.granular_temperature = fluctuation[b] / (3.0 * a.mass);
    for (Tensor3d* t : {&a.kinetic_stress, &a.contact_stress}) {
      t->x *= 1.0 / volume;
      t->y *= 1.0 / volume;
      t->z *= 1.0 / volume;
    }
  }
  return bins;
}

namespace {

const char* const kAxes[3] = {"x", "y", "z"};

std::string exact(double x) {
  if (std::isnan(x)) return "nan";
  char s[32];
  std::snprintf(s, sizeof(s), "%.17g", x);
  return s;
}

// The values of quantity q in bin a, in column order.
std::vector<double> values_of(AverageQuantity q, const BinAverage& a) {
  auto rows = [](const Tensor3d& t) {
    return std::vector<double>{t.x.x, t.x.y, t.x.z, t.y.x, t.y.y, t.y.z, t.z.x, t.z.y, t.z.z};
  };
  switch (q) {
    case AverageQuantity::solid_fraction: return {a.solid_fraction};
    case AverageQuantity::velocity: return {a.velocity.x, a.velocity.y, a.velocity.z};
    case AverageQuantity::granular_temperature: return {a.granular_temperature};
    case AverageQuantity::coordination: return {a.coordination};
    case AverageQuantity::stress: {
      std::vector<double> v = rows(a.kinetic_stress);
      const std::vector<double> c = rows(a.contact_stress);
      v.insert(v.end(), c.begin(), c.end());
      return v;
    }
  }
  return {};
}

}  // namespace

std::string average_csv_header(const AverageSpec& spec) {
  std::string h = "time,step,particles,mass";
  for (AverageQuantity q : spec.quantities) {
    const std::string name = quantity_name(q);
    if (q == AverageQuantity::velocity) {
      for (const char* a : kAxes) h += ",velocity_" + std::string(a);
    } else if (q == AverageQuantity::stress) {
      for (const char* part : {"kinetic", "contact"})
        for (const char* a : kAxes)
          for (const char* b : kAxes) h += ",stress_" + std::string(part) + "_" + a + b;
    } else {
      h += "," + name;
    }
  }
  return h;
}

std::string average_csv_row(const AverageSpec& spec, const BinAverage& a, double time, long long step) {
  std::string row = exact(time) + "," + std::to_string(step) + "," + std::to_string(a.particles) + "," + exact(a.mass);
  for (AverageQuantity q : spec.quantities)
    for (double v : values_of(q, a)) row += "," + exact(v);
  return row;
}

GridShape average_grid_shape(const AverageSpec& spec) {
  GridShape g;
  g.origin = spec.min;
  const Vec3d size = spec.max - spec.min;
  g.spacing = Vec3d(size.x / spec.bins[0], size.y / spec.bins[1], size.z / spec.bins[2]);
  g.cells = spec.bins;
  return g;
}

std::vector<GridField> average_grid_fields(const AverageSpec& spec, const std::vector<BinAverage>& bins) {
  std::vector<GridField> fields;
  GridField count{"particles", 1, {}};
  for (const BinAverage& a : bins) count.values.push_back(double(a.particles));
  fields.push_back(count);
  for (AverageQuantity q : spec.quantities) {
    const std::size_t n = values_of(q, BinAverage{}).size();
    if (q == AverageQuantity::stress) {
      GridField kinetic{"stress_kinetic", 9, {}}, contact{"stress_contact", 9, {}};
      for (const BinAverage& a : bins) {
        const std::vector<double> v = values_of(q, a);
        kinetic.values.insert(kinetic.values.end(), v.begin(), v.begin() + 9);
        contact.values.insert(contact.values.end(), v.begin() + 9, v.end());
      }
      fields.push_back(kinetic);
      fields.push_back(contact);
      continue;
    }
    GridField f{quantity_name(q), int(n), {}};
    for (const BinAverage& a : bins) {
      const std::vector<double> v = values_of(q, a);
      f.values.insert(f.values.end(), v.begin(), v.end());
    }
    fields.push_back(f);
  }
  return fields;
}

}  // namespace gs
