// Strumming (docs/physics.md §13): the drag amplification of a strumming cable against the critical angle it
// must tow at, the shedding frequency against the flow normal to that straight cable, and the string modes of a
// hanging cable against the closed-form travel time of a transverse wave, with a clump splitting it in two.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/analysis/strumming.h"

namespace tow_sim
{
namespace
{
// The steady tow of `model` behind a tow point at the origin moving at velocity_W, analysed.
StrummingAnalysis analyse(const ChainModel& model, const Eigen::Vector3d& velocity_W, double bandwidth = 0.2)
{
  const EquilibriumResult eq = steadyTowEquilibrium(model, 0.0, Eigen::Vector3d::Zero(), velocity_W);
  Eigen::Matrix3Xd joints(3, eq.state.x.cols() + 1);
  joints << Eigen::Vector3d::Zero(), eq.state.x;
  const Eigen::Matrix3Xd velocities = velocity_W.replicate(1, joints.cols());
  return strummingAnalysis(model, model.initialGeometry(), 0.0, joints, velocities, eq.tensions, bandwidth);
}

double weightInWater(const CableParams& cable, const Environment& env)  // [N/m]
{
  return (cable.mass_per_length - env.water_density * kPi * 0.25 * cable.diameter * cable.diameter) * env.gravity;
}

// A free cable (no tangential drag, its end one more segment) towed at 2 m/s lies at the critical angle of its
// normal drag: cos phi / sin^2 phi = C2 U^2 / w. Strumming multiplies C2 by the law's factor, written out here.
struct CriticalAngle
{
  double angle;            // [rad] of the middle segment below the horizontal
  double closed_form;      // [rad]
  double shedding;         // [Hz] the middle segment's
  double shedding_closed;  // [Hz] St U sin(phi_c) / D
};

CriticalAngle towFreeCable(StrummingLaw law, double amplitude, double factor)
{
  CableParams cable;
  cable.segments = 50;
  cable.length = 200.0;
  cable.tangential_drag_coefficient = 0.0;
  cable.strumming = law;
  cable.strumming_amplitude = amplitude;
  const Environment env;
  EndElementParams end = test::endLikeSegment(cable);
  end.normal_drag_coefficient *= factor;  // the end body does not strum: give it the cable's amplified drag
  auto model = test::makeModel(cable, end, env);
  const double speed = 2.0;
  const StrummingAnalysis a = analyse(*model, Eigen::Vector3d(speed, 0, 0));
  const EquilibriumResult eq = steadyTowEquilibrium(*model, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(speed, 0, 0));
  const double w = weightInWater(cable, env);
  const double c2u2 = factor * 0.5 * env.water_density * cable.normal_drag_coefficient * cable.diameter * speed * speed;
  CriticalAngle r;
  r.closed_form = std::acos((-w + std::sqrt(w * w + 4.0 * c2u2 * c2u2)) / (2.0 * c2u2));
  const Eigen::Vector3d s = eq.state.x.col(25) - eq.state.x.col(24);
  r.angle = std::atan2(-s.z(), s.head<2>().norm());
  r.shedding = a.segments[25].shedding_frequency;  // segment 26, between x_26 and x_27 (the same straight part)
  r.shedding_closed = cable.strouhal_number * speed * std::sin(r.closed_form) / cable.diameter;
  return r;
}

TEST(Strumming, AmplifiedDragTowsTheCableAtItsCriticalAngle)
{
  const double a = 0.8;                                                              // A/D
  const double vandiver = 1.0 + 1.043 * std::pow(2.0 * (a / std::sqrt(2.0)), 0.65);  // 2 A_rms / D, A_rms = A/sqrt 2
  const double blevins = 1.0 + 2.1 * a;
  const CriticalAngle none = towFreeCable(StrummingLaw::kNone, a, 1.0);
  const CriticalAngle v = towFreeCable(StrummingLaw::kVandiver, a, vandiver);
  const CriticalAngle b = towFreeCable(StrummingLaw::kBlevins, a, blevins);
  for (const CriticalAngle* c : { &none, &v, &b })
  {
    std::printf(
        "strumming: middle of a free cable at %.4f deg, closed form %.4f deg; shedding %.5f Hz, closed form "
        "%.5f Hz\n",
        c->angle * 180 / kPi, c->closed_form * 180 / kPi, c->shedding, c->shedding_closed);
    EXPECT_NEAR(c->angle, c->closed_form, 0.02 * kPi / 180);
    EXPECT_NEAR(c->shedding, c->shedding_closed, 1e-3 * c->shedding_closed);
  }
  // More drag, a flatter cable: the laws move it by degrees, a hundred times the tolerance.
  EXPECT_GT(none.closed_form - v.closed_form, 2.0 * kPi / 180);
  EXPECT_GT(v.closed_form - b.closed_form, 1.0 * kPi / 180);
}

// A cable hanging in still water from a heavy end body: T(l) = W + w (L - l), so a transverse wave crosses it in
// tau = 2 sqrt(m_t) (sqrt(W + w L) - sqrt(W)) / w; a clump at the middle splits it into two such strings.
double travelTime(double top_tension, double bottom_tension, double w, double m_t)
{
  return 2.0 * std::sqrt(m_t) * (std::sqrt(top_tension) - std::sqrt(bottom_tension)) / w;
}

TEST(Strumming, HangingCableStringModesMatchTheTravelTimeOfItsWaves)
{
  CableParams cable;
  cable.length = 400.0;
  cable.segments = 80;
  const Environment env;
  EndElementParams end;
  end.mass = 2000.0;
  end.displaced_volume = 0.2;
  JointBody clump;
  clump.joint = 40;  // 40 segments aft of it: at 200 m
  clump.mass = 500.0;
  clump.displaced_volume = 0.05;
  auto model =
      std::make_shared<ChainModel>(std::vector<CableParams>{ cable }, std::vector<JointBody>{ clump },
                                   std::make_shared<RigidEndElement>(end, NumericsParams()), env, NumericsParams());
  const StrummingAnalysis a = analyse(*model, Eigen::Vector3d::Zero());
  const double w = weightInWater(cable, env);
  const double m_t = cable.mass_per_length +
                     cable.added_mass_coefficient * env.water_density * 0.25 * kPi * cable.diameter * cable.diameter;
  const double end_weight = (end.mass - env.water_density * end.displaced_volume) * env.gravity;
  const double clump_weight = (clump.mass - env.water_density * clump.displaced_volume) * env.gravity;
  const double half = 0.5 * cable.length;
  const double lower = travelTime(end_weight + w * half, end_weight, w, m_t);
  const double upper =
      travelTime(end_weight + clump_weight + 2.0 * w * half, end_weight + clump_weight + w * half, w, m_t);
  ASSERT_EQ(a.spans.size(), 2u);
  std::printf("strumming: hanging spans' travel times %.6f s and %.6f s, closed form %.6f s and %.6f s\n",
              a.spans[0].travel_time, a.spans[1].travel_time, upper, lower);
  EXPECT_NEAR(a.spans[0].travel_time, upper, 1e-5 * upper);
  EXPECT_NEAR(a.spans[1].travel_time, lower, 1e-5 * lower);
  EXPECT_NEAR(a.spans[0].end, half, 1e-9);
  EXPECT_DOUBLE_EQ(a.spans[0].fundamental, 0.5 / a.spans[0].travel_time);
  EXPECT_EQ(a.segments[39].span, 0);
  EXPECT_EQ(a.segments[40].span, 1);
  // Still water: nothing sheds, no mode can lock in.
  for (const StrummingSpan& s : a.spans)
    EXPECT_EQ(s.dominant_mode, 0);
  for (const StrummingSegment& s : a.segments)
    EXPECT_EQ(s.lowest_mode, 0);
}

// In a tow, every segment's band holds exactly the modes within f_s (1 +- b), and the dominant mode is the one
// the most cable has in its band, counted here mode by mode.
TEST(Strumming, LockInBandsAndTheDominantModeFollowTheirDefinitions)
{
  CableParams cable;
  cable.length = 300.0;
  cable.segments = 60;
  const Environment env;
  auto model = test::makeModel(cable, EndElementParams(), env);
  const double b = 0.2;
  const StrummingAnalysis a = analyse(*model, Eigen::Vector3d(1.5, 0.3, 0.0), b);
  ASSERT_EQ(a.spans.size(), 1u);
  const double f1 = a.spans[0].fundamental;
  long highest = 0;
  for (const StrummingSegment& s : a.segments)
  {
    ASSERT_GT(s.lowest_mode, 0);
    EXPECT_LE(s.lowest_mode, s.highest_mode);
    EXPECT_GE(s.lowest_mode * f1, s.shedding_frequency * (1 - b) * (1 - 1e-12));
    EXPECT_LT((s.lowest_mode - 1) * f1, s.shedding_frequency * (1 - b));
    EXPECT_LE(s.highest_mode * f1, s.shedding_frequency * (1 + b) * (1 + 1e-12));
    EXPECT_GT((s.highest_mode + 1) * f1, s.shedding_frequency * (1 + b));
    highest = std::max(highest, s.highest_mode);
  }
  long best = 0;
  double best_length = 0.0;
  for (long k = 1; k <= highest; ++k)
  {
    double length = 0.0;
    for (const StrummingSegment& s : a.segments)
      if (s.lowest_mode <= k && k <= s.highest_mode)
        length += cable.segmentLength();
    if (length > best_length + 1e-9)
    {
      best = k;
      best_length = length;
    }
  }
  EXPECT_EQ(a.spans[0].dominant_mode, best);
  EXPECT_NEAR(a.spans[0].power_in_length, best_length, 1e-9);
  EXPECT_NEAR(a.spans[0].dominant_frequency, best * f1, 1e-12 * best * f1);
}

TEST(Strumming, RefusesABadBandwidthOrAmplitude)
{
  CableParams cable;
  cable.segments = 10;
  auto model = test::makeModel(cable, EndElementParams(), Environment());
  for (double b : { -0.1, 1.0, std::nan("") })
  {
    try
    {
      analyse(*model, Eigen::Vector3d(1, 0, 0), b);
      ADD_FAILURE() << "bandwidth " << b << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("bandwidth"), std::string::npos) << e.what();
    }
  }
  cable.strumming = StrummingLaw::kVandiver;
  for (double amplitude : { 0.0, -1.0, 3.5 })
  {
    cable.strumming_amplitude = amplitude;
    try
    {
      validate(cable);
      ADD_FAILURE() << "amplitude " << amplitude << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("cable.strumming_amplitude"), std::string::npos) << e.what();
    }
  }
  cable.strumming_amplitude = 1.0;
  cable.strouhal_number = 0.0;
  try
  {
    validate(cable);
    ADD_FAILURE() << "a Strouhal number of 0 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cable.strouhal_number"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tow_sim
