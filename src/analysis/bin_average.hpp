#pragma once
// Averages over a box cut into bins (docs/MEASUREMENTS.md). A particle
// belongs, whole, to the bin holding its centre (no sphere-bin intersection):
// the solid fraction of a bin is the volume of the spheres centred in it over
// the bin's volume, exact on average over bins several diameters wide and
// noisy over narrower ones. Per bin, with m_i, v_i the particles centred in
// it and V the bin volume:
//   solid fraction  phi = sum (4/3 pi r_i^3) / V
//   velocity        u = sum m_i v_i / sum m_i
//   temperature     T = sum m_i |v_i - u|^2 / (3 sum m_i)      [m^2/s^2]
//   coordination    Z = sum c_i / N  (c_i: particle contacts of i)
//   stress          sigma = (sum m_i v'_i (x) v'_i + sum S_i) / V,  v' = v - u,
//                   S_i the particle's contact share (core/contact_measure.hpp);
//                   compression positive, kinetic and contact parts apart.
// Sums run over the particles in id order: the same bits whatever the rank count.
#include <array>
#include <vector>

#include "core/contact_measure.hpp"
#include "core/particle_snapshot.hpp"
#include "io/h5_grid.hpp"
#include "scene/measurement_spec.hpp"

namespace gs {

struct BinAverage {
  long long particles = 0;
  double mass = 0;             // [kg]
  double solid_fraction = 0;
  Vec3d velocity;              // [m/s]; zero in an empty bin
  double granular_temperature = 0;  // [m^2/s^2]
  double coordination = 0;     // NaN in an empty bin
  Tensor3d kinetic_stress, contact_stress;  // [Pa]
};

// The bin of a point, or -1 outside the box; bins are numbered x fastest:
// (ix, iy, iz) -> ix + nx (iy + ny iz). A point on the box's max face is in
// the last bin.
long long bin_of(const AverageSpec& spec, const Vec3d& x);

// One average per bin. `contacts`: per particle of `s` (same order), needed
// only for coordination and stress (else may be empty: those stay zero).
std::vector<BinAverage> bin_averages(const AverageSpec& spec, const ParticleSnapshot& s,
                                     const std::vector<ContactMeasure>& contacts);

// The average log (docs/OUTPUT.md): time, step, particles, mass, then the
// spec's quantities in its order (velocity_x..z; stress_kinetic_xx..zz and
// stress_contact_xx..zz by rows).
std::string average_csv_header(const AverageSpec& spec);
std::string average_csv_row(const AverageSpec& spec, const BinAverage& a, double time, long long step);
// The grid of a binned average: particles per bin, then the spec's quantities.
GridShape average_grid_shape(const AverageSpec& spec);
std::vector<GridField> average_grid_fields(const AverageSpec& spec, const std::vector<BinAverage>& bins);

}  // namespace gs
