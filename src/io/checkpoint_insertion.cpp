#include "io/checkpoint_insertion.hpp"

namespace gs {
namespace {

// Per inlet, one value each: the state's fields as columns.
struct Columns {
  std::vector<std::uint64_t> inserted, batches;
  std::vector<double> mass;
};

Columns columns(const InsertionState& s) {
  Columns c;
  for (const InletState& i : s.inlets) {
    c.inserted.push_back(i.inserted);
    c.mass.push_back(i.mass);
    c.batches.push_back(i.batches);
  }
  return c;
}

}  // namespace

void write_insertion(const h5::File& f, const InsertionState& s) {
  const Columns c = columns(s);
  h5::create_group(f, "insertion");
  h5::write_attribute(f, "insertion", "next_id", std::uint64_t(s.next_id));
  h5::write_vector(f, "insertion/inserted", c.inserted);
  h5::write_vector(f, "insertion/mass", c.mass);
  h5::write_vector(f, "insertion/batches", c.batches);
}

std::optional<InsertionState> read_insertion(const h5::File& f) {
  if (!h5::exists(f, "insertion")) return std::nullopt;
  InsertionState s;
  s.next_id = h5::read_attribute<std::uint64_t>(f, "insertion", "next_id");
  const std::vector<hsize_t> dims = h5::dims_of(f, "insertion/inserted");
  if (dims.size() != 1) throw std::runtime_error("insertion/inserted is not one-dimensional");
  const std::vector<std::uint64_t> inserted = h5::read_array<std::uint64_t>(f, "insertion/inserted", dims);
  const std::vector<double> mass = h5::read_array<double>(f, "insertion/mass", dims);
  const std::vector<std::uint64_t> batches = h5::read_array<std::uint64_t>(f, "insertion/batches", dims);
  for (std::size_t i = 0; i < inserted.size(); ++i) s.inlets.push_back({inserted[i], mass[i], batches[i]});
  return s;
}

void add_insertion(Fnv1a64& sum, const InsertionState& s) {
  const Columns c = columns(s);
  sum.add_value(std::uint64_t(s.next_id));
  sum.add_value(std::uint64_t(s.inlets.size()));
  sum.add_array(c.inserted);
  sum.add_array(c.mass);
  sum.add_array(c.batches);
}

}  // namespace gs
