// The load limits: which limit the largest tension exceeds, where, and the configuration's refusals.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tow_sim/core/run/tension_limits.h"

namespace tow_sim
{
namespace
{
Eigen::Matrix3Xd tensions(std::initializer_list<double> magnitudes)
{
  Eigen::Matrix3Xd t(3, static_cast<Eigen::Index>(magnitudes.size()));
  Eigen::Index j = 0;
  for (double m : magnitudes)
    t.col(j++) = m * Eigen::Vector3d(0.6, 0.0, 0.8);  // a unit direction
  return t;
}

TEST(TensionLimits, TheLargestTensionAgainstEachLimit)
{
  CableParams cable;
  const Eigen::Matrix3Xd t = tensions({ 900.0, 1200.0, 700.0 });
  TensionLimitCheck none = checkTensionLimits(cable, t);
  EXPECT_EQ(none.level, TensionLimitCheck::Level::kWithin);  // no limits set
  EXPECT_NEAR(none.largest, 1200.0, 1e-9);
  EXPECT_EQ(none.joint, 1);
  cable.safe_working_load = 1200.0;  // equal is within
  EXPECT_EQ(checkTensionLimits(cable, t).level, TensionLimitCheck::Level::kWithin);
  cable.safe_working_load = 1000.0;
  EXPECT_EQ(checkTensionLimits(cable, t).level, TensionLimitCheck::Level::kAboveWorkingLoad);
  cable.breaking_load = 1100.0;
  EXPECT_EQ(checkTensionLimits(cable, t).level, TensionLimitCheck::Level::kAboveBreakingLoad);
  cable.safe_working_load.reset();  // a breaking load alone
  EXPECT_EQ(checkTensionLimits(cable, tensions({ 1000.0 })).level, TensionLimitCheck::Level::kWithin);
  EXPECT_EQ(checkTensionLimits(cable, t).level, TensionLimitCheck::Level::kAboveBreakingLoad);
}

TEST(TensionLimits, TheWorseOfTwoChecks)
{
  TensionLimitCheck warn, error, bigger_warn;
  warn.level = bigger_warn.level = TensionLimitCheck::Level::kAboveWorkingLoad;
  error.level = TensionLimitCheck::Level::kAboveBreakingLoad;
  warn.largest = 10.0;
  error.largest = 5.0;  // an error outranks a larger tension below the breaking load
  bigger_warn.largest = 20.0;
  EXPECT_EQ(&TensionLimitCheck::worse(warn, error), &error);
  EXPECT_EQ(&TensionLimitCheck::worse(error, warn), &error);
  EXPECT_EQ(&TensionLimitCheck::worse(warn, bigger_warn), &bigger_warn);
}

TEST(TensionLimits, ABreakingLoadBelowTheWorkingLoadIsRefusedNamingBoth)
{
  CableParams cable;
  cable.safe_working_load = 5000.0;
  cable.breaking_load = 4000.0;
  try
  {
    validate(cable, "cable");
    FAIL() << "accepted a breaking load below the safe working load";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("cable.breaking_load = 4000"), std::string::npos) << what;
    EXPECT_NE(what.find("safe_working_load"), std::string::npos) << what;
  }
  cable.breaking_load = 5000.0;
  EXPECT_NO_THROW(validate(cable, "cable"));
  cable.safe_working_load = -1.0;
  EXPECT_THROW(validate(cable, "cable"), std::invalid_argument);
}

}  // namespace
}  // namespace tow_sim
