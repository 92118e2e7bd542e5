#include "comm/contact_measure_gather.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace gs {

std::vector<ContactMeasure> gather_contact_measures(Transport& transport, const std::vector<ParticleId>& local_ids,
                                                    const std::vector<ContactMeasure>& local) {
  if (local_ids.size() != local.size()) throw std::logic_error("contact measures do not match their particles");
  if (transport.size() == 1) return local;
  // Each record: the id, then the measure, copied as bytes.
  constexpr std::size_t kRecord = sizeof(ParticleId) + sizeof(ContactMeasure);
  Bytes mine(local.size() * kRecord);
  for (std::size_t i = 0; i < local.size(); ++i) {
    std::memcpy(mine.data() + i * kRecord, &local_ids[i], sizeof(ParticleId));
    std::memcpy(mine.data() + i * kRecord + sizeof(ParticleId), &local[i], sizeof(ContactMeasure));
  }
  const std::vector<Bytes> parts = transport.gather(std::move(mine));
  if (transport.rank() != 0) return {};
  std::vector<ParticleId> id;
  std::vector<ContactMeasure> all;
  for (const Bytes& b : parts) {
    if (b.size() % kRecord != 0) throw std::runtime_error("contact measure message truncated");
    for (std::size_t at = 0; at < b.size(); at += kRecord) {
      ParticleId k;
      ContactMeasure m;
      std::memcpy(&k, b.data() + at, sizeof(ParticleId));
      std::memcpy(&m, b.data() + at + sizeof(ParticleId), sizeof(ContactMeasure));
      id.push_back(k);
      all.push_back(m);
    }
  }
  std::vector<std::size_t> order(id.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  std::vector<ContactMeasure> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = all[order[k]];
  return sorted;
}

}  // namespace gs
