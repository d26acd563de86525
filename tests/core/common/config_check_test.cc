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

namespace msb {
namespace {

TEST(Utf8, ValidAndInvalidSequences) {
  EXPECT_TRUE(isValidUtf8(""));
  EXPECT_TRUE(isValidUtf8("plain ascii"));
  EXPECT_TRUE(isValidUtf8("m\xc2\xb2 \xe2\x89\x88 \xf0\x9f\x9a\x81"));  // m², ≈, a helicopter
  EXPECT_FALSE(isValidUtf8("\xff"));
  EXPECT_FALSE(isValidUtf8("a\xc3\x28"));         // bad continuation
  EXPECT_FALSE(isValidUtf8("\xc0\xaf"));          // overlong '/'
  EXPECT_FALSE(isValidUtf8("\xed\xa0\x80"));      // a surrogate
  EXPECT_FALSE(isValidUtf8("\xf4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(isValidUtf8("\xe2\x89"));          // truncated
}

}  // namespace
}  // namespace msb
