#pragma once
// Fields on a regular grid of cells (the measurements' bin averages,
// docs/OUTPUT.md) as one HDF5 file per time, and an XDMF 3 index over them: a
// temporal collection of 3DCoRectMesh grids with cell-centred attributes, so
// ParaView opens the whole series as one structured grid.
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gs {

// One field: `components` values per cell (1 scalar, 3 vector, 9 tensor by
// rows), cells numbered x fastest: (ix, iy, iz) -> ix + nx (iy + ny iz).
struct GridField {
  std::string name;
  int components = 1;
  std::vector<double> values;  // cells * components
};

struct GridShape {
  Vec3d origin;               // the grid's min corner [m]
  Vec3d spacing;              // cell size [m]
  std::array<int, 3> cells{1, 1, 1};
  long long cell_count() const { return 1LL * cells[0] * cells[1] * cells[2]; }
};

// Writes /<name> of shape (nz, ny, nx[, components]) for every field, and
// the root attributes time, step and fields (the names in order), and the
// datasets origin, spacing and cells; atomically (io/atomic_file.hpp). Every
// HDF5 call checked.
void write_grid_h5(const std::string& path, const GridShape& shape, const std::vector<GridField>& fields, double time,
                   long long step);

struct GridSeriesEntry {
  double time = 0;
  long long step = 0;
  std::string h5_file;  // relative to the .xdmf file's directory
  GridShape shape;
  std::vector<std::pair<std::string, int>> fields;  // name, components
};

// Reads back what write_grid_h5 wrote (to index a series again after a restart).
GridSeriesEntry read_grid_entry(const std::string& directory, const std::string& h5_file);

std::string grid_xdmf_text(const std::string& name, const std::vector<GridSeriesEntry>& entries);
void write_grid_xdmf(const std::string& path, const std::string& name, const std::vector<GridSeriesEntry>& entries);

}  // namespace gs
