#pragma once
// ParticleRemoval over an execution policy `Exec` (CpuExec or CudaExec). A
// step without a removal costs one pass over the owned positions and the
// read-back of one count; a step with one selects the leaving particles
// (their fields cross to the host) and compacts the others through
// ParticleMovement::keep_owned.
#include "engine/particle_mover.hpp"
#include "engine/particle_removal.hpp"

namespace gs {

template <class Exec>
class ParticleRemover final : public ParticleRemoval {
 public:
  explicit ParticleRemover(ParticleMovement& movement)
      : movement_(movement), outlets_(Exec::backend), exit_(Exec::backend), found_(Exec::backend, 1),
        list_(Exec::backend), fields_(Exec::backend), scratch_(Exec::backend) {}

  void set_exits(const Exits& exits, const Vec3d& domain_lo, const Vec3d& domain_hi) override {
    outlets_.from_host(exits.outlets);
    exit_of_ = ExitOf{nullptr, std::int32_t(exits.outlets.size()), exits.open_faces, domain_lo, domain_hi};
    active_ = exits.any();
  }

  Index remove(ParticleStore& s, long long step, std::vector<RemovedParticle>& removed) override {
    const Index n = s.n_owned;
    if (!active_ || n == 0) return 0;
    exit_.resize(std::size_t(n));
    found_.zero();
    ExitOf exit_of = exit_of_;
    exit_of.outlets = outlets_.data();
    Exec::parallel_for(n, TagExits{s.position.data(), exit_of, exit_.data(), found_.data()});
    if (found_.to_host()[0] == 0) return 0;

    list_.resize(std::size_t(n));
    const Index m = Exec::select(n, ExitTagged{exit_.data(), true}, list_.data(), scratch_);
    list_.resize(std::size_t(m));
    const std::vector<ParticleId> id = gathered(s.id);
    const std::vector<float> mass = gathered(s.mass);
    const std::vector<std::int32_t> exit = gathered(exit_);
    const std::vector<std::uint8_t> material = gathered(s.material), marker = gathered(s.marker);
    for (Index k = 0; k < m; ++k)
      removed.push_back({step, id[k], mass[k], exit[k], material[k], marker[k]});

    list_.resize(std::size_t(n));
    list_.resize(std::size_t(Exec::select(n, ExitTagged{exit_.data(), false}, list_.data(), scratch_)));
    movement_.keep_owned(s, list_);
    return m;
  }

  std::size_t bytes() const override {
    return outlets_.bytes() + exit_.bytes() + found_.bytes() + list_.bytes() + fields_.bytes() + scratch_.bytes();
  }

 private:
  // Field `a` of the particles in list_, on the host.
  template <class T>
  std::vector<T> gathered(const DeviceArray<T>& a) {
    fields_.resize(list_.size() * sizeof(T));
    gather_into<Exec>(a, list_, fields_.data());
    std::vector<T> out(list_.size());
    if (!out.empty()) backend_copy_to_host(Exec::backend, out.data(), fields_.data(), out.size() * sizeof(T));
    return out;
  }

  ParticleMovement& movement_;
  ExitOf exit_of_{};
  bool active_ = false;
  DeviceArray<OutletRegion> outlets_;
  DeviceArray<std::int32_t> exit_;  // per owned particle: its exit, or kNoExit
  DeviceArray<unsigned> found_;     // how many have one
  DeviceArray<Index> list_;         // store indices: the leaving, then the staying particles
  DeviceArray<unsigned char> fields_, scratch_;
};

}  // namespace gs
