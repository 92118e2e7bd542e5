#pragma once
// Who may touch whom: the cell list and a Verlet list of the particles
// within reach plus a skin (both backends). The force computation of the same run reads what this part built.
#include <cstddef>

#include "engine/particle_store.hpp"
#include "neighbor/cell_grid.hpp"

namespace gs {

// The owned particles split by whether their Verlet list names a ghost, from
// the list's last build: the forces of the interior ones (none) need nothing
// the ghosts' forward brings, so a rank computes them while that forward is
// in flight (Simulation::compute_forces), and the boundary ones after it.
struct GhostSplit {
  const Index* order = nullptr;  // backend memory: the interior's store indices, ascending, then the boundary's
  Index interior = 0, boundary = 0;
  bool valid() const { return order != nullptr; }  // false where the build saw no ghost
};

class NeighbourSearch {
 public:
  virtual ~NeighbourSearch() = default;

  // Bins the whole store (owned and ghosts) into the grid's cells.
  virtual void build_cell_list(const ParticleStore& s, const CellGrid& grid) = 0;
  // Store indices in cell order, from the last cell list (one per particle
  // binned): the order ParticleMovement::reorder sorts memory into.
  virtual const DeviceArray<Index>& cell_order() const = 0;
  // Whether contacts come from a Verlet list rather than from the cell list
  // every step: the grid's cells must then hold the skin too.
  virtual bool uses_verlet_list() const = 0;
  // What the force computation needs to find contacts: the cell list, and
  // with a Verlet list the list too, of particles within r_i + r_j + skin.
  virtual void build(const ParticleStore& s, const CellGrid& grid, double skin) = 0;
  // The kick-drift measures the moves against the Verlet list
  // (engine/integrator.hpp) and stale() reads its verdict, held to half of
  // `skin` where that is narrower than the list's: with ranks the halo's
  // skin, which the coarse cells may cut (RankExchange::set_skin), so that
  // the verdict is also the halo's (RankExchange::halo_stale).
  virtual void watch_moves(double skin) = 0;
  // Whether build() must run before this step's force computation, called
  // after this step's kick-drift: always without a Verlet list; with one,
  // when the store has changed since the build (ParticleStore::revision)
  // or, where moves are watched, when the verdict of the last step's
  // kick-drift says so (neighbor/verlet_list.hpp, ListWatch): waiting for
  // that kernel only, while this step's runs.
  virtual bool stale(const ParticleStore& s) = 0;
  virtual GhostSplit ghost_split() const = 0;
  virtual std::size_t bytes() const = 0;  // cell and Verlet lists
};

}  // namespace gs
