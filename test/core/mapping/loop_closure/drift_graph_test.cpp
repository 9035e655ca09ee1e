#include "hex_slam/mapping/loop_closure/drift_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace mapping {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> From(int source, int size) {
  std::vector<double> start(size, kInf);
  start[source] = 0.0;
  return start;
}

// A trajectory of submaps 10 m of path apart: with no loop closed, the drift between two
// submaps is the path between them, whichever way it is counted.
TEST(DriftGraphTest, WithoutTiesTheDriftIsThePathBetween) {
  DriftGraph graph(1000.0);
  for (int s = 0; s < 8; ++s) graph.AddSubmap(10.0 * s);
  const std::vector<double> from3 = graph.Spread(From(3, 8));
  for (int s = 0; s < 8; ++s) EXPECT_DOUBLE_EQ(from3[s], 10.0 * std::abs(s - 3)) << s;
}

// A long corridor loop: submaps 0-19 out, the robot back near submap 2 at submap 20. A loop
// closed there ties 20 to 2: 2's neighbours are near, as far as their path from 2. The middle
// of the loop (submap 10), which no constraint ties, stays as far as the path either way;
// a revisit elsewhere does not make it near.
TEST(DriftGraphTest, ARevisitBringsNearOnlyWhatItTies) {
  DriftGraph graph(1000.0);
  for (int s = 0; s <= 21; ++s) graph.AddSubmap(10.0 * s);
  graph.Tie(20, 2);
  const std::vector<double> from21 = graph.Spread(From(21, 22));
  EXPECT_DOUBLE_EQ(from21[2], 10.0);   // 21 -> 20 (10 m), tied to 2
  EXPECT_DOUBLE_EQ(from21[0], 30.0);   // then back along the old trajectory
  EXPECT_DOUBLE_EQ(from21[5], 40.0);
  EXPECT_DOUBLE_EQ(from21[10], 90.0);  // by the tie and on, shorter than back along (110 m)
  EXPECT_DOUBLE_EQ(from21[15], 60.0);  // back along, shorter than by the tie (140 m)
}

// Ties are symmetric, repeated ties change nothing, and a tie to oneself is no tie.
TEST(DriftGraphTest, TiesAreSymmetricAndIdempotent) {
  DriftGraph graph(1000.0);
  for (int s = 0; s < 6; ++s) graph.AddSubmap(5.0 * s);
  graph.Tie(5, 0);
  const long version = graph.version();
  graph.Tie(0, 5);
  graph.Tie(3, 3);
  EXPECT_EQ(graph.version(), version);
  EXPECT_DOUBLE_EQ(graph.Spread(From(0, 6))[5], 0.0);
  EXPECT_DOUBLE_EQ(graph.Spread(From(5, 6))[0], 0.0);
  EXPECT_DOUBLE_EQ(graph.Spread(From(1, 6))[4], 10.0);  // 1 -> 0 -> 5 -> 4
}

// Beyond the horizon every drift reads as the horizon, so a spread stays local.
TEST(DriftGraphTest, DriftIsCappedAtTheHorizon) {
  DriftGraph graph(25.0);
  for (int s = 0; s < 10; ++s) graph.AddSubmap(10.0 * s);
  const std::vector<double> from0 = graph.Spread(From(0, 10));
  EXPECT_DOUBLE_EQ(from0[2], 20.0);
  for (int s = 3; s < 10; ++s) EXPECT_DOUBLE_EQ(from0[s], 25.0) << s;
}

TEST(DriftGraphTest, RefusesBadInput) {
  EXPECT_THROW(DriftGraph(-1.0), std::invalid_argument);
  EXPECT_THROW(DriftGraph(std::nan("")), std::invalid_argument);
  DriftGraph graph(10.0);
  graph.AddSubmap(5.0);
  EXPECT_THROW(graph.AddSubmap(4.0), std::invalid_argument);
  EXPECT_THROW(graph.AddSubmap(kInf), std::invalid_argument);
  EXPECT_THROW(graph.Tie(0, 1), std::out_of_range);
  EXPECT_THROW(graph.Spread({}), std::invalid_argument);
}

// Against Floyd–Warshall over the same graph (consecutive submaps joined by their paths' gap,
// ties free), on random trajectories and ties, from random several-source starts.
TEST(DriftGraphTest, MatchesAllPairsShortestPaths) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 2 + static_cast<int>(rng() % 30);
    const double horizon = std::uniform_real_distribution<double>(5.0, 200.0)(rng);
    DriftGraph graph(horizon);
    std::vector<double> first(n);
    double path = 0.0;
    for (int s = 0; s < n; ++s) {
      path += std::uniform_real_distribution<double>(0.0, 15.0)(rng);
      first[s] = path;
      graph.AddSubmap(path);
    }
    std::vector<std::vector<double>> d(n, std::vector<double>(n, kInf));
    for (int s = 0; s < n; ++s) {
      d[s][s] = 0.0;
      if (s + 1 < n) d[s][s + 1] = d[s + 1][s] = first[s + 1] - first[s];
    }
    const int ties = static_cast<int>(rng() % (n + 1));
    for (int k = 0; k < ties; ++k) {
      const int a = static_cast<int>(rng() % n);
      const int b = static_cast<int>(rng() % n);
      graph.Tie(a, b);
      d[a][b] = d[b][a] = 0.0;
    }
    for (int k = 0; k < n; ++k) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
      }
    }
    std::vector<double> start(n, kInf);
    for (int s = 0; s < n; ++s) {
      if (rng() % 3 == 0) start[s] = std::uniform_real_distribution<double>(0.0, 50.0)(rng);
    }
    const std::vector<double> spread = graph.Spread(start);
    for (int t = 0; t < n; ++t) {
      double expected = horizon;
      for (int s = 0; s < n; ++s) expected = std::min(expected, start[s] + d[s][t]);
      EXPECT_NEAR(spread[t], expected, 1e-9) << "trial " << trial << " submap " << t;
    }
  }
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
