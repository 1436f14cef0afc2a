// Every invalid parameter is rejected with a message naming the parameter, the value and the range.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/chain_fixtures.h"

namespace tow_sim
{
namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Builds a model after `edit` and expects std::invalid_argument whose message holds every `needle`.
void expectRejected(const std::function<void(CableParams&, EndElementParams&, Environment&, NumericsParams&)>& edit,
                    const std::vector<std::string>& needles)
{
  CableParams cable;
  EndElementParams end;
  Environment env;
  NumericsParams num;
  edit(cable, end, env, num);
  try
  {
    test::makeModel(cable, end, env, num);
    ADD_FAILURE() << "accepted; expected a message with '" << needles.front() << "'";
  }
  catch (const std::invalid_argument& error)
  {
    const std::string message = error.what();
    for (const std::string& needle : needles)
      EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message << "\nmissing: " << needle;
  }
}

TEST(Params, DefaultsAreValid)
{
  EXPECT_NO_THROW(test::makeModel(CableParams(), EndElementParams(), Environment()));
}

TEST(Params, CableValuesOutOfRangeAreNamed)
{
  using C = CableParams;
  using E = EndElementParams;
  using V = Environment;
  using N = NumericsParams;
  expectRejected([](C& c, E&, V&, N&) { c.length = -1.0; }, { "cable.length", "-1", "(0, 100000]", "[m]" });
  expectRejected([](C& c, E&, V&, N&) { c.length = 0.0; }, { "cable.length", "= 0" });
  expectRejected([](C& c, E&, V&, N&) { c.length = kNaN; }, { "cable.length", "nan" });
  expectRejected([](C& c, E&, V&, N&) { c.segments = 0; }, { "cable.segments", "= 0", "[1, 100000]" });
  expectRejected([](C& c, E&, V&, N&) { c.segments = 1000000; }, { "cable.segments", "1000000" });
  expectRejected([](C& c, E&, V&, N&) { c.diameter = 0.0; }, { "cable.diameter" });
  expectRejected([](C& c, E&, V&, N&) { c.mass_per_length = -2.0; }, { "cable.mass_per_length", "-2" });
  expectRejected([](C& c, E&, V&, N&) { c.mass_per_length = kInf; }, { "cable.mass_per_length", "inf" });
  expectRejected([](C& c, E&, V&, N&) { c.normal_drag_coefficient = -0.1; }, { "cable.normal_drag_coefficient" });
  expectRejected([](C& c, E&, V&, N&) { c.tangential_drag_coefficient = kNaN; },
                 { "cable.tangential_drag_coefficient" });
  expectRejected([](C& c, E&, V&, N&) { c.c1 = -1.0; }, { "cable.c1" });
  expectRejected([](C& c, E&, V&, N&) { c.c2 = kNaN; }, { "cable.c2" });
  expectRejected([](C& c, E&, V&, N&) { c.added_mass_coefficient = -1.0; }, { "cable.added_mass_coefficient" });
}

TEST(Params, EnvironmentAndNumericsValuesOutOfRangeAreNamed)
{
  using C = CableParams;
  using E = EndElementParams;
  using V = Environment;
  using N = NumericsParams;
  expectRejected([](C&, E&, V& v, N&) { v.water_density = -1.0; }, { "environment.water_density", "-1" });
  expectRejected([](C&, E&, V& v, N&) { v.gravity = kNaN; }, { "environment.gravity" });
  expectRejected([](C&, E&, V& v, N&) { v.current_W.y() = kInf; }, { "environment.current[1]", "inf" });
  expectRejected([](C&, E&, V& v, N&) { v.current_W.x() = 50.0; }, { "environment.current[0]", "50" });
  expectRejected([](C&, E&, V&, N& n) { n.abs_tol = 0.0; }, { "numerics.abs_tol" });
  expectRejected([](C&, E&, V&, N& n) { n.rel_tol = kNaN; }, { "numerics.rel_tol" });
  expectRejected([](C&, E&, V&, N& n) { n.max_step = -1.0; }, { "numerics.max_step" });
  expectRejected([](C&, E&, V&, N& n) { n.fixed_step = 5.0; }, { "numerics.fixed_step" });
  expectRejected([](C&, E&, V&, N& n) { n.tangential_smoothing_speed = 0.0; },
                 { "numerics.tangential_smoothing_speed" });
}

TEST(Params, EndElementValuesOutOfRangeAreNamed)
{
  using C = CableParams;
  using E = EndElementParams;
  using V = Environment;
  using N = NumericsParams;
  expectRejected([](C&, E& e, V&, N&) { e.mass = 0.0; }, { "end_element.mass" });
  expectRejected([](C&, E& e, V&, N&) { e.length = kNaN; }, { "end_element.length" });
  expectRejected([](C&, E& e, V&, N&) { e.cg_from_bail = 3.0; }, { "end_element.cg_from_bail", "3" });
  expectRejected([](C&, E& e, V&, N&) { e.cb_from_bail = -0.5; }, { "end_element.cb_from_bail" });
  expectRejected([](C&, E& e, V&, N&) { e.displaced_volume = -1.0; }, { "end_element.displaced_volume" });
  expectRejected([](C&, E& e, V&, N&) { e.transverse_inertia = 0.0; }, { "end_element.transverse_inertia" });
  expectRejected([](C&, E& e, V&, N&) { e.diameter = kInf; }, { "end_element.diameter" });
}

TEST(Params, SimulatorRejectsBadStatesAndTimes)
{
  auto model = test::makeModel(CableParams(), EndElementParams(), Environment());
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  ChainState wrong_size;
  wrong_size.x.setZero(3, 5);
  wrong_size.v.setZero(3, 5);
  EXPECT_THROW(sim.reset(0.0, wrong_size), std::invalid_argument);
  ChainState good = straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  ChainState bad = good;
  bad.v(2, 3) = kNaN;
  EXPECT_THROW(sim.reset(0.0, bad), std::invalid_argument);
  sim.reset(10.0, good);
  EXPECT_THROW(sim.advanceTo(5.0), std::invalid_argument);
  EXPECT_THROW(sim.advanceTo(kNaN), std::invalid_argument);
  EXPECT_THROW(sim.setCurrent(Eigen::Vector3d(kNaN, 0.0, 0.0)), std::invalid_argument);
  EXPECT_EQ(sim.data().environment.current_W, Eigen::Vector3d::Zero());  // unchanged after the rejection
}

}  // namespace
}  // namespace tow_sim
