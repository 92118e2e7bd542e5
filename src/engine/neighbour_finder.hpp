#pragma once
// NeighbourSearch over an execution policy: the cell list, and the Verlet
// list where the policy keeps one (Exec::verlet_list: both backends), with
// the verdicts of the watched kick-drifts on its staleness.
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "backend/backend.hpp"
#include "backend/host_flags.hpp"
#include "engine/neighbour_search.hpp"
#include "neighbor/cell_list.hpp"
#include "neighbor/verlet_list.hpp"

namespace gs {

// Told when the Verlet list is about to be replaced or invalidated (it still
// describes the store it was built on, unless the store changed since), when
// a new one is about to be built (before the cell list is sorted: neither
// the cell list nor the staging buffer is held then) and when it is built:
// the pair history (engine/pair_carry.hpp) keeps its springs per list
// entry. Its tables take entry_bytes() per entry; it frees them before the
// new list is built and allocates them anew once it is.
struct ListFollower {
  virtual void list_replacing(const ParticleStore& s) = 0;
  virtual void list_building(const ParticleStore& s) = 0;
  virtual void list_built(const ParticleStore& s) = 0;
  virtual std::size_t entry_bytes() const = 0;

 protected:
  ~ListFollower() = default;
};

template <class Exec>
class NeighbourFinder final : public NeighbourSearch {
 public:
  // `scratch`: the step's staging buffer (engine/step_state.hpp), which
  // holds the cell list's sort buffers while it is built.
  explicit NeighbourFinder(DeviceArray<unsigned char>& scratch)
      : cells_(Exec::backend), verlet_(Exec::backend), split_order_(Exec::backend), scratch_(scratch),
        verdicts_(Exec::backend) {
    // As many lanes per particle as the forces take (GRAINSTORM_FORCE_LANES, read once).
    if constexpr (Exec::backend == Backend::cuda) verlet_.lanes_setting = force_lanes_setting();
  }

  void build_cell_list(const ParticleStore& s, const CellGrid& grid) override {
    retire_list(s);
    sort_cells(s, grid);
  }
  const DeviceArray<Index>& cell_order() const override { return cells_.sorted; }
  bool uses_verlet_list() const override { return Exec::verlet_list; }
  // A build holds at once only what one of its phases needs, each transient
  // freed before the next phase allocates: the follower keeps its contacts
  // before the cell list is sorted (beside neither the cell list nor what a
  // re-sort left in the staging buffer) and frees its old tables, the sort's
  // buffers (in the staging buffer) go before the new list comes, the cell
  // list before the follower's new tables, the kept contacts before the
  // reference positions. So between builds a run holds neither the cell
  // list nor a staging buffer (docs/PERFORMANCE.md, "A build's transients
  // one after another", "The contacts kept before the sort").
  void build(const ParticleStore& s, const CellGrid& grid, double skin) override {
    retire_list(s);
    if constexpr (Exec::verlet_list) {
      cells_.discard();
      scratch_.discard();
      if (follower_) follower_->list_building(s);
      sort_cells(s, grid);
      scratch_.discard();
      if constexpr (Exec::backend == Backend::cuda) verlet_.staged_width = staged_width(s);
      build_verlet_list<Exec>(verlet_, cells_, s.position.data(), s.radius.data(), s.id.data(), s.n_owned, s.size(),
                              skin);
      last_entries_ = verlet_.list.size();
      cells_.discard();
      split_by_ghosts(s);
      built_at_ = s.revision;
      ++builds_;
      if (follower_) follower_->list_built(s);
      set_list_references<Exec>(verlet_, s.position.data());
    } else {
      sort_cells(s, grid);
    }
  }
  void follow(ListFollower* f) { follower_ = f; }
  // The list itself, for its follower (which takes its arrays when it
  // detaches: engine/pair_carry.hpp).
  VerletList& verlet() { return verlet_; }
  const VerletList& verlet() const { return verlet_; }
  void watch_moves(double skin) override {
    watching_ = true;
    watch_skin_ = skin;
  }
  bool stale(const ParticleStore& s) override {
    if (!list_valid(s)) return true;
    if (!watching_) return false;
    if (!(watched_skin() > 0)) return true;  // no skin: any move may bring a new contact
    // The last step's verdict: the kick-drift of a step's kernels ago.
    const Watched& before = watched_[slot(latest_ - 1)];
    if (latest_ > 0 && before.step == latest_ - 1) {
      const ListVerdict v = verdicts_.read(slot(before.step));
      if (before.builds != builds_) return v.fast != 0;  // built since, on the positions that kick-drift left
      if (!before.with_list) return true;
      note_outrun(before.step, v);
      return v.stale_now != 0 || v.stale_next != 0;
    }
    // None (the first step of this run): this step's own, read at once.
    const Watched& now = watched_[slot(latest_)];
    if (latest_ >= 0 && now.step == latest_ && now.builds == builds_ && now.with_list)
      return verdicts_.read(slot(now.step)).stale_now != 0;
    return true;
  }
  // The check the kick-drift of `step` makes (inactive where moves are not
  // watched), its verdict's slot armed; watch_queued once it is launched.
  ListWatch watch(const ParticleStore& s, long long step) {
    const double skin = watched_skin();
    if (!watching_ || !(skin > 0)) return {};
    const bool with_list = list_valid(s);
    watched_[slot(step)] = {step, builds_, with_list};
    // The margin covers a step's change of a move, whatever skin is watched:
    // the list's share of it.
    return {with_list ? verlet_.reference.data() : nullptr, verlet_.box, 0.5 * skin,
            kListMarginOfSkin * verlet_.skin, verdicts_.arm(slot(step))};
  }
  void watch_queued(long long step) {
    verdicts_.queued(slot(step));
    latest_ = step;
  }
  // The first step for which a kept list was found stale a step late (or
  // none), clearing it: reported with the kernels' faults. The last step's
  // verdict, which no stale() has read yet, is read here (the caller has
  // waited for the device: a fault check).
  Fault take_fault() {
    const Watched& last = watched_[slot(latest_)];
    if (latest_ >= 0 && last.step == latest_ && last.builds == builds_ && last.with_list)
      note_outrun(last.step, verdicts_.read(slot(last.step)));
    return std::exchange(outrun_, Fault{kFaultNone, 0, 0});
  }
  GhostSplit ghost_split() const override { return split_; }
  std::size_t bytes() const override {  // not scratch_: the mover's
    return cells_.bytes() + verlet_.bytes() + split_order_.bytes();
  }

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
  // The list about to be replaced: the follower takes the history it keeps
  // per entry, and what is left of the list goes before anything a build
  // allocates.
  void retire_list(const ParticleStore& s) {
    if (follower_) follower_->list_replacing(s);
    discard_spent_list(verlet_);
    split_ = {};
  }
  void sort_cells(const ParticleStore& s, const CellGrid& grid) {
    build_cells<Exec>(cells_, s.position.data(), s.id.data(), s.size(), grid, scratch_);
  }

  // The ghost split of a list just built over a store with ghosts (none
  // without: a single rank's store has none, and keeps no array for it). Two
  // stable selections into one array of the owned particles' indices; their
  // counts come back to the host, as the list's total did.
  void split_by_ghosts(const ParticleStore& s) {
    split_ = {};
    if (s.size() == s.n_owned) {
      split_order_.discard();
      return;
    }
    split_order_.resize_discarding(std::size_t(s.n_owned));
    const ListOffset* begin = verlet_.begin.data();
    const Index* list = verlet_.list.data();
    Index* order = split_order_.data();
    DeviceArray<unsigned char>& scratch = verlet_.scan_scratch;
    split_.interior = Exec::select(s.n_owned, ListNamesGhost{begin, list, s.n_owned, false}, order, scratch);
    split_.boundary =
        Exec::select(s.n_owned, ListNamesGhost{begin, list, s.n_owned, true}, order + split_.interior, scratch);
    split_.order = order;
  }

  // A GPU build's rows in one pass (staged_list_width) take the room of the
  // follower's tables of the last list, which the follower has freed and
  // allocates anew once this list is built, less the cell list held beside
  // the rows: so they hold no more than the phase that kept the contacts
  // (which held those tables) or the merge (which holds them anew).
  int staged_width(const ParticleStore& s) const {
    const std::size_t tables = follower_ ? follower_->entry_bytes() * last_entries_ : 0;
    const std::size_t cells = cells_.bytes();
    return staged_list_width(tables > cells ? tables - cells : 0, last_entries_, std::size_t(s.n_owned));
  }

  CellList cells_;
  VerletList verlet_;  // empty where Exec::verlet_list is false
  std::size_t last_entries_ = 0;  // the last list's entries
  DeviceArray<Index> split_order_;  // GhostSplit::order's storage
  GhostSplit split_;
  DeviceArray<unsigned char>& scratch_;
  std::uint64_t built_at_ = 0;  // the store's revision at the Verlet list's build
  std::uint64_t builds_ = 0;    // Verlet list builds so far
  ListFollower* follower_ = nullptr;

  // A watched kick-drift: its step, the builds before it, and whether the
  // list described the store then (else it measured moves only).
  struct Watched {
    long long step = -1;
    std::uint64_t builds = 0;
    bool with_list = false;
  };
  static int slot(long long step) { return int(step & 1); }
  double watched_skin() const { return std::min(verlet_.skin, watch_skin_); }
  // The verdict of `step`, for which the list was kept on the verdict of the
  // step before: the list must have covered it (the lag's guard).
  void note_outrun(long long step, const ListVerdict& v) {
    if (v.stale_now != 0 && outrun_.code == kFaultNone) outrun_ = Fault{kFaultListOutrun, v.stale_now_particle, step};
  }
  bool watching_ = false;
  double watch_skin_ = 0;  // watch_moves's
  HostFlags<ListVerdict> verdicts_;
  Watched watched_[HostFlagRing::kSlots];
  long long latest_ = -1;  // the step of the last watched kick-drift
  Fault outrun_{kFaultNone, 0, 0};
};

}  // namespace gs
