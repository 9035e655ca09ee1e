#include "hex_slam/scan_matcher.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(ScanMatcherTest, DecimationKeepsPointsAtLeastTheSpacingFromTheLastKept) {
  const std::vector<Eigen::Vector2d> points = {{0.0, 0.0}, {0.05, 0.0}, {0.09, 0.0}, {0.11, 0.0},
                                               {0.15, 0.0}, {0.3, 0.0}};
  std::vector<Eigen::Vector2d> kept;
  DecimateScan(points, 0.1, &kept);
  // 0.05 and 0.09 are within 0.1 of 0; 0.11 is not; 0.15 is within 0.1 of 0.11.
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0], points[0]);
  EXPECT_EQ(kept[1], points[3]);
  EXPECT_EQ(kept[2], points[5]);
  DecimateScan(points, 0.0, &kept);
  EXPECT_EQ(kept, points);
  std::vector<Eigen::Vector2d> visited;
  ForEachKeptEndpoint(points, 0.1, [&visited](const Eigen::Vector2d& p) { visited.push_back(p); });
  DecimateScan(points, 0.1, &kept);
  EXPECT_EQ(visited, kept);
  DecimateScan({}, 0.1, &kept);
  EXPECT_TRUE(kept.empty());
}

TEST(ScanMatcherTest, EndpointMoveBoundIsTranslationPlusTurnTimesReach) {
  const std::vector<Eigen::Vector2d> points = {{3.0, 4.0}, {-1.0, 0.5}};
  EXPECT_DOUBLE_EQ(Reach(points), 5.0);
  EXPECT_DOUBLE_EQ(Reach({}), 0.0);
  const Pose2 from(1.0, 2.0, 0.1), to(1.3, 2.4, 0.3);
  EXPECT_DOUBLE_EQ(EndpointMoveBound(from, to, 5.0), 0.5 + 0.2 * 5.0);
  // It bounds every endpoint's actual move.
  for (const Eigen::Vector2d& p : points) {
    EXPECT_LE(((to * p) - (from * p)).norm(), EndpointMoveBound(from, to, Reach(points)) + 1e-12);
  }
  // Across ±π the turn is the short way round.
  EXPECT_NEAR(EndpointMoveBound(Pose2(0, 0, M_PI - 0.01), Pose2(0, 0, -M_PI + 0.01), 1.0), 0.02,
              1e-12);
}

TEST(ScanMatcherTest, HectorsMethodTurnsOffWhatHexSlamAdds) {
  ScanMatcherOptions options;
  options.max_iterations_fine = 7;
  options.coarsest_min_move_cells = 0.25;
  UseHectorsMethod(&options);
  EXPECT_FALSE(options.subcell_offsets);
  EXPECT_TRUE(options.verify_converged_step);
  EXPECT_FALSE(options.angle_tolerance_from_range);
  EXPECT_EQ(options.coarsest_min_move_cells, 0.0);
  EXPECT_EQ(options.max_iterations_fine, 7);  // the rest is kept
  EXPECT_TRUE(options.Validate().empty());
  options.coarsest_min_move_cells = -1.0;
  ASSERT_EQ(options.Validate().size(), 1u);
  EXPECT_NE(options.Validate()[0].find("scan_match_coarsest_min_move_cells"), std::string::npos);
}

TEST(ScanMatcherTest, AngleToleranceMovesTheMeanEndpointAsFarAsTheTranslationTolerance) {
  ScanMatcherOptions options;
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.002, 4.0), 0.0005);
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.004, 4.0), 0.001);  // a coarser level
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.002, 0.0), options.angle_tolerance);  // no points
  options.angle_tolerance_from_range = false;
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.004, 4.0), options.angle_tolerance);
  EXPECT_DOUBLE_EQ(MeanRange({{3.0, 4.0}, {0.0, 1.0}}), 3.0);
  EXPECT_DOUBLE_EQ(MeanRange({}), 0.0);
}

}  // namespace
}  // namespace hex_slam
