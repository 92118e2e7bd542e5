#pragma once
// What the measurements of a run observe and how often (docs/MEASUREMENTS.md):
// plain data, held by SceneSpec and read by analysis/flow_measure.hpp and
// analysis/bin_average.hpp.
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "walls/triangle_mesh.hpp"

namespace gs {

// When a measurement is evaluated: at start, start + every, ... (engine/schedule.hpp).
struct MeasurementTimes {
  double every = 0;  // simulated seconds between evaluations (> 0)
  double start = 0;  // simulated time of the first evaluation [s]
};

// Flow through a surface: the plane through `point` with unit `normal`,
// bounded by a disk (`radius` > 0) or a rectangle (`half_lengths` > 0 along
// `axis_u` and `axis_v` = normal x axis_u), or unbounded; or a triangle mesh
// (`surface`, each triangle's normal from its winding; point and normal unused).
enum class FlowBound { none, disk, rectangle, mesh };

struct FlowSpec {
  std::string name;  // output file flow_<name>.csv
  Vec3d point, normal;
  FlowBound bound = FlowBound::none;
  double radius = 0;                    // disk
  Vec3d axis_u, axis_v;                 // rectangle, unit, in the plane
  double half_length_u = 0, half_length_v = 0;
  TriangleMesh surface;                 // mesh
  std::vector<int> markers;             // markers with a row of their own (the rows per material always exist)
  MeasurementTimes times;
};

// What a region average reports (docs/MEASUREMENTS.md): each an enum value,
// named as in the scene file.
enum class AverageQuantity { solid_fraction, velocity, granular_temperature, coordination, stress };

// Averages over the box [min, max], cut into bins[0] x bins[1] x bins[2]
// equal bins (1 1 1: the box as one region).
struct AverageSpec {
  std::string name;  // output files average_<name>.csv and, for a grid, average_<name>.xdmf
  Vec3d min, max;
  std::array<int, 3> bins{1, 1, 1};
  std::vector<AverageQuantity> quantities;
  MeasurementTimes times;
  int bin_count() const { return bins[0] * bins[1] * bins[2]; }
  bool needs_contacts() const;  // coordination or stress
};

struct MeasurementsSpec {
  std::vector<FlowSpec> flows;
  std::vector<AverageSpec> averages;
  bool empty() const { return flows.empty() && averages.empty(); }
  bool needs_contacts() const;
};

// The name a quantity has in scene files and output headers.
const char* quantity_name(AverageQuantity q);
// All quantities, in the order of quantity_name's enum.
const std::vector<AverageQuantity>& all_quantities();

}  // namespace gs
