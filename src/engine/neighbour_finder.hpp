#pragma once
// NeighbourSearch over an execution policy: the cell list, and the Verlet
// list where the policy keeps one (Exec::verlet_list: both backends).
#include <stdexcept>

#include "engine/neighbour_search.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

template <class Exec>
class NeighbourFinder final : public NeighbourSearch {
 public:
  // `scratch`: the step's staging buffer (engine/step_state.hpp), which
  // holds the cell list's sort buffers while it is built.
  explicit NeighbourFinder(DeviceArray<unsigned char>& scratch)
      : cells_(Exec::backend), verlet_(Exec::backend), scratch_(scratch) {}

  void build_cell_list(const ParticleStore& s, const CellGrid& grid) override {
    build_cells<Exec>(cells_, s.position.data(), s.id.data(), s.size(), grid, scratch_);
    verlet_.valid = false;
  }
  const DeviceArray<Index>& cell_order() const override { return cells_.sorted; }
  bool uses_verlet_list() const override { return Exec::verlet_list; }
  void build(const ParticleStore& s, const CellGrid& grid, double skin) override {
    build_cell_list(s, grid);
    if constexpr (Exec::verlet_list) {
      build_verlet_list<Exec>(verlet_, cells_, s.position.data(), s.radius.data(), s.id.data(), s.n_owned, s.size(),
                              skin);
      built_at_ = s.revision;
    }
  }
  bool stale(const ParticleStore& s, bool check_moves) const override {
    if constexpr (Exec::verlet_list)
      return !list_valid(s) ||
             (check_moves && verlet_list_stale<Exec>(verlet_, s.position.data(), s.n_owned, s.size()));
    return true;
  }
  std::size_t bytes() const override { return cells_.bytes() + verlet_.bytes(); }  // not scratch_: the mover's

  // What the force computation reads.
  CellCandidates cell_candidates(const ParticleStore& s) const {
    // A cell list of another store would send the kernel to wrong indices.
    if (cells_.sorted.size() != std::size_t(s.size())) throw std::logic_error("forces before the cell list was built");
    return {cells_.grid, cells_.sorted.data(), cells_.cell_begin.data()};
  }
  // Whether the Verlet list describes the store as it is now.
  bool list_valid(const ParticleStore& s) const { return verlet_.valid && built_at_ == s.revision; }
  ListCandidates list_candidates() const { return verlet_.candidates(); }
  // The periodic box of the grid the cell list was built on.
  const PeriodicBox& box() const { return cells_.grid.box; }

 private:
  CellList cells_;
  VerletList verlet_;  // empty where Exec::verlet_list is false
  DeviceArray<unsigned char>& scratch_;
  std::uint64_t built_at_ = 0;  // the store's revision at the Verlet list's build
};

}  // namespace gs
