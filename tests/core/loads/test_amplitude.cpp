// The amplitude of a load or a prescribed motion (docs/theory.md (5b.1)) and the rules the scene
// validator reports with their JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/loads/amplitude.hpp"

namespace stoss::loads {
namespace {

TEST(Amplitude, WithoutPointsTheFactorIsOne) {
  const Amplitude a;
  EXPECT_EQ(a(-3.0), 1.0);
  EXPECT_EQ(a(0.0), 1.0);
  EXPECT_EQ(a(1e9), 1.0);
}

TEST(Amplitude, IsLinearBetweenPointsAndConstantBeyondTheEnds) {
  const Amplitude a({{0.5, 2.0}, {1.5, 4.0}, {2.0, -1.0}});
  EXPECT_DOUBLE_EQ(a(0.0), 2.0) << "before the first point: its factor";
  EXPECT_DOUBLE_EQ(a(0.5), 2.0);
  EXPECT_DOUBLE_EQ(a(1.0), 3.0);
  EXPECT_DOUBLE_EQ(a(1.5), 4.0);
  EXPECT_DOUBLE_EQ(a(1.75), 1.5);
  EXPECT_DOUBLE_EQ(a(2.0), -1.0);
  EXPECT_DOUBLE_EQ(a(7.0), -1.0) << "after the last point: its factor";
}

TEST(Amplitude, OnePointIsAConstant) {
  const Amplitude a({{3.0, 0.25}});
  EXPECT_DOUBLE_EQ(a(0.0), 0.25);
  EXPECT_DOUBLE_EQ(a(5.0), 0.25);
}

TEST(AmplitudeRules, TimesMustIncreaseAndThePointerNamesTheLaterTime) {
  const auto broken = amplitude_rule_broken({{0, 0}, {1, 1}, {1, 2}});
  ASSERT_TRUE(broken);
  EXPECT_EQ(broken->where, "/2/0");
  EXPECT_NE(broken->rule.find("times must be increasing"), std::string::npos) << broken->rule;
  EXPECT_NE(broken->rule.find("1 follows 1"), std::string::npos) << broken->rule;
  EXPECT_EQ(amplitude_rule_broken({{0, 0}, {2, 1}, {1, 2}})->where, "/2/0");
}

TEST(AmplitudeRules, TimesAndFactorsMustBeFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto time = amplitude_rule_broken({{0, 0}, {nan, 1}});
  ASSERT_TRUE(time);
  EXPECT_EQ(time->where, "/1/0");
  EXPECT_NE(time->rule.find("times must be finite"), std::string::npos) << time->rule;
  const auto factor = amplitude_rule_broken({{0, inf}});
  ASSERT_TRUE(factor);
  EXPECT_EQ(factor->where, "/0/1");
  EXPECT_NE(factor->rule.find("factors must be finite"), std::string::npos) << factor->rule;
}

TEST(AmplitudeRules, ADisplacementStartsAtZero) {
  EXPECT_FALSE(amplitude_rule_broken({{0, 0}, {1, 1}}, AmplitudeUse::displacement));
  EXPECT_FALSE(amplitude_rule_broken({{-1, -1}, {1, 1}}, AmplitudeUse::displacement))
      << "a(0) = 0 between points";
  EXPECT_FALSE(amplitude_rule_broken({{0, 1}, {1, 1}}, AmplitudeUse::load)) << "a load may start loaded";
  const auto broken = amplitude_rule_broken({{0.5, 0.5}, {1, 1}}, AmplitudeUse::displacement);
  ASSERT_TRUE(broken);
  EXPECT_EQ(broken->where, "");
  EXPECT_NE(broken->rule.find("a(0) = 0.5"), std::string::npos) << broken->rule;
}

TEST(AmplitudeRules, TheConstructorRefusesWhatTheRulesRefuse) {
  try {
    Amplitude({{1, 0}, {0, 1}});
    FAIL() << "decreasing times accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("amplitude/1/0: an amplitude's times must be increasing"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace stoss::loads
