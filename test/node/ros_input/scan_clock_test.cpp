#include "ros_input/scan_clock.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

TEST(ScanClockTest, ClassifiesStepsBackAgainstTheThreshold) {
  ScanClock clock(1.0);
  EXPECT_EQ(clock.Check(100.0), StampOrder::kInOrder);  // the first scan
  clock.Accept(100.0);
  EXPECT_EQ(clock.Check(100.0), StampOrder::kInOrder);  // a repeat is not backwards
  EXPECT_EQ(clock.Check(100.1), StampOrder::kInOrder);
  EXPECT_EQ(clock.Check(99.5), StampOrder::kSlightlyEarlier);
  EXPECT_EQ(clock.Check(99.0), StampOrder::kSlightlyEarlier);  // exactly the threshold
  EXPECT_EQ(clock.Check(98.99), StampOrder::kJumpedBack);
  EXPECT_EQ(clock.Check(0.0), StampOrder::kJumpedBack);
}

TEST(ScanClockTest, OnlyAcceptedStampsMoveTheClock) {
  ScanClock clock(1.0);
  clock.Accept(10.0);
  // A checked-but-not-accepted stamp (e.g. a malformed scan from the far future) changes nothing.
  EXPECT_EQ(clock.Check(1e9), StampOrder::kInOrder);
  EXPECT_EQ(clock.Check(10.5), StampOrder::kInOrder);
  clock.Accept(10.5);
  EXPECT_EQ(*clock.last(), 10.5);
  clock.Reset();
  EXPECT_FALSE(clock.last().has_value());
  EXPECT_EQ(clock.Check(0.0), StampOrder::kInOrder);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
