#include "core/common/clock.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace msb {
namespace {

TEST(TickClock, TimeIsDerivedFromIntegerTicks) {
  TickClock clock(500);
  for (int i = 0; i < 1000; ++i) clock.advance();
  EXPECT_EQ(clock.tick(), 1000);
  EXPECT_DOUBLE_EQ(clock.seconds(), 2.0);
  EXPECT_EQ(clock.ticksFor(1200.0), 600000);
}

TEST(TickClock, DivisorsMustDivideThePhysicsRate) {
  TickClock clock(500);
  EXPECT_EQ(clock.divisorFor(250, "controller"), 2);
  EXPECT_EQ(clock.divisorFor(5, "map"), 100);
  EXPECT_THROW(clock.divisorFor(15, "camera"), std::invalid_argument);
  EXPECT_THROW(clock.divisorFor(0, "x"), std::invalid_argument);
  EXPECT_THROW(clock.divisorFor(1000, "x"), std::invalid_argument);
}

TEST(RateSchedule, FiresExactlyRateTimesPerSecondAtTheFirstTickOfEachPeriod) {
  for (double rate : {200.0, 15.0, 4.5, 500.0, 1.0}) {
    RateSchedule s(500, rate, "stage");
    int count = 0;
    int64_t last = -1;
    for (int64_t t = 0; t < 1000; ++t) {  // two seconds
      if (!s.due(t)) continue;
      // The k-th firing is the first tick at or after k / rate seconds.
      const double k_period_ticks = count * 500.0 / rate;
      EXPECT_GE(t + 1e-9, k_period_ticks) << rate;
      EXPECT_LT(t - 1.0, k_period_ticks) << rate;
      EXPECT_GT(t, last);
      last = t;
      ++count;
    }
    EXPECT_NEAR(count, 2.0 * rate, 1.0) << rate;
  }
}

TEST(RateSchedule, RejectsRatesAboveThePhysicsRate) {
  EXPECT_THROW(RateSchedule(500, 600, "imu"), std::invalid_argument);
  EXPECT_THROW(RateSchedule(500, 0, "imu"), std::invalid_argument);
}

}  // namespace
}  // namespace msb
