// Rows in id order without an order array (engine/row_order.hpp): where the
// owned ids are dense, each window of rows is found by a scatter over every
// store index; checked against the order the host sorts (core/id_order.hpp)
// for every window of a shuffled set of ids. And the chunks a GPU's output
// puts in order at a time (engine/output_chunk.hpp), against their rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "backend/cpu/cpu_exec.hpp"
#include "core/id_order.hpp"
#include "engine/output_chunk.hpp"
#include "engine/row_order.hpp"

namespace gs {
namespace {

// to[k] = from[i] and the store index itself, row k of a window.
struct RowAndSource {
  const double* from;
  double* to;
  Index* source;
  void operator()(Index k, Index i) const {
    to[k] = from[i];
    source[k] = i;
  }
};

TEST(RowOrder, ScatterByIdPutsEveryWindowsRowsInIdOrder) {
  constexpr Index n = 1000;
  constexpr ParticleId lowest = 7;
  std::vector<ParticleId> id(n);
  std::iota(id.begin(), id.end(), lowest);
  std::shuffle(id.begin(), id.end(), std::mt19937(5));
  std::vector<double> field(n);
  for (Index i = 0; i < n; ++i) field[std::size_t(i)] = 0.5 * i + 1e-3 * id[std::size_t(i)];
  const std::vector<std::size_t> order = id_order(id);  // the host's: store indices by ascending id
  const RowOrder scatter = RowOrder::scatter(id.data(), lowest, n);
  for (Index window : {Index(1), Index(7), Index(333), n}) {
    const auto rows = static_cast<std::size_t>(window);
    std::vector<double> to(rows);
    std::vector<Index> source(rows);
    for (Index first = 0; first < n; first += window) {
      const Index m = std::min(window, n - first);
      std::fill(source.begin(), source.end(), Index(-1));
      for_rows<CpuExec>(scatter, first, m, RowAndSource{field.data(), to.data(), source.data()});
      for (Index k = 0; k < m; ++k) {
        const std::size_t want = order[std::size_t(first + k)];
        ASSERT_EQ(source[std::size_t(k)], Index(want)) << "window " << window << ", row " << first + k;
        EXPECT_EQ(to[std::size_t(k)], field[want]);
      }
      for (Index k = m; k < window; ++k) EXPECT_EQ(source[std::size_t(k)], Index(-1)) << "beyond the window";
    }
  }
}

TEST(RowOrder, GatherAndStoreOrder) {
  const std::vector<double> field = {10, 11, 12, 13};
  const std::vector<Index> order = {2, 0, 3, 1};
  std::vector<double> to(2);
  std::vector<Index> source(2);
  for_rows<CpuExec>(RowOrder::gather(order.data()), 1, 2, RowAndSource{field.data(), to.data(), source.data()});
  EXPECT_EQ(source, (std::vector<Index>{0, 3}));
  EXPECT_EQ(to, (std::vector<double>{10, 13}));
  for_rows<CpuExec>(RowOrder{}, 2, 2, RowAndSource{field.data(), to.data(), source.data()});
  EXPECT_EQ(source, (std::vector<Index>{2, 3}));
}

TEST(OutputChunk, AThirtySecondOfAFieldOrAByteARowUnlessTheStagingIsLarger) {
  constexpr std::size_t kMiB = std::size_t(1) << 20, row = 24;  // an fp64 vector per particle
  // 4e6 positions (96 MB): a 32nd, 3 MB; 64e6 (1.5 GB): 48 MB.
  EXPECT_EQ(output_chunk_rows(4000000, row, 0), Index(3000000 / row));
  EXPECT_EQ(output_chunk_rows(64000000, row, 0), Index(48000000 / row));
  // 4e8 (9.6 GB): 64 MiB at most.
  EXPECT_EQ(output_chunk_rows(400000000, row, 0), Index(64 * kMiB / row));
  // Rows of contact history (12 slots of fp64 vectors): a byte a row, 4 MB at 4e6.
  EXPECT_EQ(output_chunk_rows(4000000, 12 * row, 0), Index(4000000 / (12 * row)));
  // A staging array larger than that: as large as it, up to 64 MiB.
  EXPECT_EQ(output_chunk_rows(4000000, row, 20 * kMiB), Index(20 * kMiB / row));
  EXPECT_EQ(output_chunk_rows(4000000, row, 200 * kMiB), Index(64 * kMiB / row));
  EXPECT_EQ(output_chunk_rows(4000000, row, 2 * kMiB), Index(3000000 / row));  // a smaller one: the 32nd
  // 1e6 (24 MB): 1 MiB at least; a small field whole.
  EXPECT_EQ(output_chunk_rows(1000000, row, 0), Index(kMiB / row));
  EXPECT_EQ(output_chunk_rows(7680, row, 0), Index(7680));
  EXPECT_EQ(output_chunk_rows(3, 1000 * kMiB, 0), Index(1));  // a row larger than any chunk: one at a time
}

}  // namespace
}  // namespace gs
