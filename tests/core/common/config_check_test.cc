#include "core/common/config_check.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

struct Inner {
  double gain = 1.0;
  void validate(ConfigChecker& c) const { c.positive("gain", gain); }
};
struct Outer {
  double rate_hz = 10.0;
  Inner inner;
  void validate(ConfigChecker& c) const {
    c.inRange("rate_hz", rate_hz, 1.0, 100.0);
    c.nested("inner", inner);
  }
};

TEST(ConfigCheck, ValidConfigPasses) { EXPECT_NO_THROW(checkValid(Outer{})); }

TEST(ConfigCheck, EveryBadKeyIsNamedWithItsPath) {
  Outer o;
  o.rate_hz = 500;
  o.inner.gain = -2;
  try {
    checkValid(o);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_EQ(e.issues()[0].key, "rate_hz");
    EXPECT_EQ(e.issues()[1].key, "inner.gain");
    EXPECT_NE(std::string(e.what()).find("inner.gain"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("got -2"), std::string::npos);
  }
}

}  // namespace
}  // namespace msb
