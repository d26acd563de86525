#include "core/common/config_fields.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>

namespace msb {
namespace {

enum class Shade { kLight, kDark };
constexpr auto wordsOf(Shade) { return std::array{std::pair{Shade::kLight, "light"}, std::pair{Shade::kDark, "dark"}}; }

TEST(WordEnum, AModeKeysWordsParseAndNameTheirValues) {
  static_assert(WordEnum<Shade>);
  static_assert(!WordEnum<int>);
  EXPECT_STREQ(wordOf(Shade::kDark), "dark");
  Shade s = Shade::kLight;
  EXPECT_TRUE(parseWord("dark", s));
  EXPECT_EQ(s, Shade::kDark);
  EXPECT_FALSE(parseWord("Dark", s));  // words are exact
  EXPECT_FALSE(parseWord("", s));
  EXPECT_EQ(s, Shade::kDark);  // unchanged by a word that is none
  EXPECT_EQ(Choices::of<Shade>().text(), "light or dark");
}

TEST(Limits, HoldsAndNamesEachKindOfInterval) {
  EXPECT_TRUE(Limits::positive().holds(1e-9));
  EXPECT_FALSE(Limits::positive().holds(0.0));
  EXPECT_EQ(Limits::positive().text(), "> 0");
  EXPECT_TRUE(Limits::nonNegative().holds(0.0));
  EXPECT_EQ(Limits::nonNegative().text(), ">= 0");
  EXPECT_TRUE(Limits::range(1, 50).holds(50));
  EXPECT_FALSE(Limits::range(1, 50).holds(50.5));
  EXPECT_EQ(Limits::range(1, 50).text(), "in [1, 50]");
  EXPECT_EQ((Limits{0.0, 20.0, true, false}).text(), "in (0, 20]");
  EXPECT_EQ(Limits::any().text(), "any number");
  EXPECT_FALSE(Limits::range(0, 1).holds(std::nan("")));
  EXPECT_TRUE(Limits::range(0, 1).orUnset().holds(std::nan("")));
}

TEST(Limits, OutsideIsRefusedByItsOwnInterval) {
  for (const Limits& l : {Limits::positive(), Limits::nonNegative(), Limits::range(0.05, 5.0),
                          Limits{0.0, 20.0, true, false}, Limits::range(-1.0, 1.0)})
    EXPECT_FALSE(l.holds(l.outside())) << l.text();
  EXPECT_TRUE(std::isnan(Limits::any().outside()));
}

// A table as a config struct declares it, checked by FieldCheck.
struct Sub {
  int n = 3;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("n", s.n, Limits::range(1, 5));
  }
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};
struct Top {
  double r_m = 1.0;
  Vec3 gains = Vec3(1, 1, 1);
  std::string mode = "a";
  bool on = true;
  Sub sub;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("r_m", s.r_m, Limits::positive());
    v.key("gains", s.gains, Limits::positive());
    v.key("mode", s.mode, Choices{"a", "b"});
    v.key("on", s.on);
    v.group("sub", s.sub);
    v.moved("old_m", "elsewhere");
  }
};

TEST(FieldCheck, NamesEveryKeyOutsideItsRuleWithItsPath) {
  Top t;
  ConfigChecker ok;
  checkFields(t, ok);
  EXPECT_TRUE(ok.issues().empty());
  t.r_m = 0;
  t.gains.y() = -1;
  t.mode = std::string("c");  // (not = "c": GCC 12 warns falsely, -Wrestrict)
  t.sub.n = 9;
  ConfigChecker bad("x.");
  checkFields(t, bad);
  ASSERT_EQ(bad.issues().size(), 4u);
  EXPECT_EQ(bad.issues()[0].key, "x.r_m");
  EXPECT_EQ(bad.issues()[0].reason, "must be > 0 (got 0)");
  EXPECT_EQ(bad.issues()[1].key, "x.gains");
  EXPECT_EQ(bad.issues()[2].reason, "must be a or b (got 'c')");
  EXPECT_EQ(bad.issues()[3].key, "x.sub.n");
  EXPECT_EQ(bad.issues()[3].reason, "must be in [1, 5] (got 9)");
}

}  // namespace
}  // namespace msb
