// Regression: beam patterns with negative offsets. The start range of such a pattern begins at -offset;
// Lattice::build_indexing once read that start before computing it, dropping the last row of beams (and
// counting phantom beams when a range was empty in two directions).
#include <gtest/gtest.h>

#include "steady/lattice/lattice.hpp"

namespace steady {
namespace {

TEST(LatticeNegativeOffsets, CountsAndIndexingMatchEnumeration) {
  const auto t = Similarity::translation;
  for (int di = -2; di <= 2; ++di)
    for (int dj = -1; dj <= 1; ++dj) {
      if (di == 0 && dj == 0) continue;
      const Lattice lat = Lattice::incremental({{{0, 0, 0}, 0.1}}, {{0, di, dj, -1, 0}}, {5, 1 + (dj != 0) * 3, 3},
                                               t({1, 0, 0}), t({0, 1, 0}), t({0, 0, 1}));
      const Counts c = lat.counts();
      std::int64_t expected = 0;
      for (std::int64_t k = 0; k < c.w; ++k)
        for (std::int64_t j = 0; j < c.v; ++j)
          for (std::int64_t i = 0; i < c.u; ++i) {
            const bool exists = i + di >= 0 && i + di < c.u && j + dj >= 0 && j + dj < c.v && k - 1 >= 0;
            EXPECT_EQ(lat.beam_exists({i, j, k, 0}), exists) << di << " " << dj << " at " << i << "," << j << "," << k;
            expected += exists;
          }
      EXPECT_EQ(lat.beam_count(), expected) << di << " " << dj;
      for (std::int64_t x = 0; x < lat.beam_count(); ++x) EXPECT_EQ(lat.beam_index(lat.beam_id(x)), x);
    }
}

}  // namespace
}  // namespace steady
