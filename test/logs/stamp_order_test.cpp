#include "hex_slam/logs/stamp_order.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

TEST(StampOrderTest, ALateStampIsLoweredToItsSuccessorAndTheRestKept) {
  // Scan 2 was stamped late (as in the Intel log); everything else is right.
  const std::vector<double> stamps = {1.0, 1.2, 2.1, 1.6, 1.8, 2.0};
  std::vector<double> out;
  EXPECT_EQ(MakeStampsNonDecreasing(stamps, &out), 1);
  EXPECT_EQ(out, (std::vector<double>{1.0, 1.2, 1.6, 1.6, 1.8, 2.0}));
  EXPECT_EQ(CountBackwardSteps(stamps), 1);
  EXPECT_EQ(CountBackwardSteps(out), 0);
}

TEST(StampOrderTest, SeveralLateStampsInARowAllComeDown) {
  const std::vector<double> stamps = {0.0, 3.0, 3.1, 1.0, 2.0};
  std::vector<double> out;
  EXPECT_EQ(MakeStampsNonDecreasing(stamps, &out), 2);
  EXPECT_EQ(out, (std::vector<double>{0.0, 1.0, 1.0, 1.0, 2.0}));
}

TEST(StampOrderTest, IncreasingKeepsAStepBelowTheSuccessorAndWorksInPlace) {
  std::vector<double> stamps = {0.0, 3.0, 3.1, 1.0, 2.0};
  EXPECT_EQ(MakeStampsIncreasing(stamps, 0.01, &stamps), 2);
  EXPECT_DOUBLE_EQ(stamps[2], 0.99);
  EXPECT_DOUBLE_EQ(stamps[1], 0.98);
  for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_LT(stamps[i - 1], stamps[i]);
}

TEST(StampOrderTest, OrderedAndEmptyInputsAreUntouched) {
  std::vector<double> out;
  EXPECT_EQ(MakeStampsNonDecreasing({}, &out), 0);
  EXPECT_TRUE(out.empty());
  const std::vector<double> ordered = {1.0, 1.0, 2.0};
  EXPECT_EQ(MakeStampsNonDecreasing(ordered, &out), 0);
  EXPECT_EQ(out, ordered);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
