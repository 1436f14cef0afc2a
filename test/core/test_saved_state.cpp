// Saved states: a batch run restored from a state saved at an output time writes the very rows the
// uninterrupted run wrote from then on (every stepper, the winch, the elastic cable, the autopilot), the
// text gives back the same doubles, a state that does not fit is refused naming the field with nothing
// changed, and a state relocated to another heading and place tows on as the original, turned (the
// model's invariance under a rotation about the vertical and a translation, in still water).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/chain_fixtures.h"
#include "temp_file.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{
Scenario shipped(const std::string& name)
{
  return loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
}

struct Output
{
  std::vector<std::string> series, shapes;  // lines without the header
  std::map<double, RunState> states;
};

std::vector<std::string> lines(const std::string& text)
{
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line))
    out.push_back(line);
  return out;
}

Output run(const Scenario& sc)
{
  std::ostringstream series, shapes;
  BatchResult result;
  Output out;
  runScenario(sc, series, shapes, result, {}, [&out](double t, const RunState& s) { out.states[t] = s; });
  out.series = lines(series.str());
  out.shapes = lines(shapes.str());
  return out;
}

// The rows of `all` from time t on (the first cell, as written).
std::vector<std::string> from(const std::vector<std::string>& all, double t)
{
  std::vector<std::string> out;
  for (const std::string& row : all)
    if (std::stod(row.substr(0, row.find(','))) >= t - 1e-9)
      out.push_back(row);
  return out;
}

// Runs `sc` saving at t_save, then again from the saved file; the rows from t_save on must be equal.
void expectBitIdenticalContinuation(Scenario sc, double t_save, const std::string& label)
{
  sc.save_state_at = { t_save };
  const Output whole = run(sc);
  ASSERT_EQ(whole.states.count(t_save), 1u) << label;
  const std::string path = ::test::writeTempFile("saved_" + label + ".txt", runStateText(whole.states.at(t_save)));
  Scenario restored = sc;
  restored.initial.type = InitialShape::Type::kFile;
  restored.initial.path = path;
  const Output rest = run(restored);
  // Saved again at once, the restored state is the saved one, field by field.
  ASSERT_EQ(rest.states.count(t_save), 1u) << label;
  EXPECT_EQ(runStateText(rest.states.at(t_save)), runStateText(whole.states.at(t_save))) << label;
  const std::vector<std::string> expected = from(whole.series, t_save);
  ASSERT_GT(expected.size(), 10u) << label;
  ASSERT_EQ(rest.series.size(), expected.size()) << label;
  for (size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(rest.series[i], expected[i]) << label << ": row " << i << " after the restore";
  const std::vector<std::string> expected_shapes = from(whole.shapes, t_save);
  ASSERT_GT(expected_shapes.size(), 0u) << label;
  EXPECT_EQ(rest.shapes, expected_shapes) << label;
}

TEST(SavedState, ARestoredBatchRunContinuesBitIdentically)
{
  // Commands and a 180-degree turn (the default implicit stepper), then with dopri5 and with rk4.
  Scenario turn = shipped("turn_180");
  turn.duration = 140.0;
  turn.shape_interval = 20.0;
  expectBitIdenticalContinuation(turn, 80.0, "turn_implicit");
  turn.config.numerics.stepper = StepperType::kDopri5;
  expectBitIdenticalContinuation(turn, 80.0, "turn_dopri5");
  turn.config.numerics.stepper = StepperType::kRk4;
  turn.duration = 100.0;
  expectBitIdenticalContinuation(turn, 70.0, "turn_rk4");
  // The autopilot on the winch (its integrals, feed-forward and track; the re-meshing layout).
  Scenario winch = shipped("autopilot_winch");
  winch.duration = 160.0;
  expectBitIdenticalContinuation(winch, 110.0, "autopilot_winch");
  // The elastic cable snapping in a heave (its slack flags and snap count).
  Scenario snap = shipped("heave_snap");
  snap.duration = 40.0;
  expectBitIdenticalContinuation(snap, 27.0, "heave_snap");  // nine of ten segments slack then
}

TEST(SavedState, TheTextGivesBackTheSameDoubles)
{
  Scenario sc = shipped("autopilot_winch");
  sc.duration = 30.0;
  sc.save_state_at = { 20.0 };
  const RunState s = run(sc).states.at(20.0);
  ASSERT_TRUE(s.autopilot);
  ASSERT_GT(s.autopilot->track.size(), 2u);
  const RunState back = parseRunState(runStateText(s), "test");
  EXPECT_EQ(runStateText(back), runStateText(s));
  EXPECT_EQ(back.sim.y, s.sim.y);  // every double equal
  EXPECT_EQ(back.sim.dt, s.sim.dt);
  EXPECT_EQ(back.autopilot->integral, s.autopilot->integral);
  EXPECT_EQ(back.autopilot->track.back(), s.autopilot->track.back());
  EXPECT_TRUE(std::isnan(back.autopilot->vehicle.received) == std::isnan(s.autopilot->vehicle.received));
  // The unset maxima: -inf and NaN survive too.
  RunState odd = s;
  odd.max_strain = -std::numeric_limits<double>::infinity();
  odd.attitude_heading = std::numeric_limits<double>::quiet_NaN();
  odd.sim.y.back() = 4.9e-320;  // a subnormal (a payout rate decaying after a stop): strtod flags ERANGE
  const RunState odd_back = parseRunState(runStateText(odd), "test");
  EXPECT_EQ(odd_back.max_strain, -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(odd_back.attitude_heading));
  EXPECT_EQ(odd_back.sim.y.back(), 4.9e-320);
}

void expectRefusal(const std::string& text, const std::string& words)
{
  try
  {
    parseRunState(text, "bad.txt");
    ADD_FAILURE() << "accepted: " << text.substr(0, 200);
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.txt"), std::string::npos) << e.what();
  }
}

// The text with the line starting with `key ` replaced (or removed when `line` is empty).
std::string withLine(const std::string& text, const std::string& key, const std::string& line)
{
  std::istringstream in(text);
  std::string out, l;
  while (std::getline(in, l))
    if (l == key || l.compare(0, key.size() + 1, key + " ") == 0)
    {
      if (!line.empty())
        out += line + "\n";
    }
    else
      out += l + "\n";
  return out;
}

TEST(SavedState, BadFilesAreRefusedNamingTheField)
{
  Scenario sc = shipped("turn_180");
  sc.duration = 10.0;
  sc.save_state_at = { 10.0 };
  const std::string good = runStateText(run(sc).states.at(10.0));
  EXPECT_NO_THROW(parseRunState(good, "good.txt"));
  expectRefusal("", "not a tow_sim state");
  expectRefusal("t 5\n" + good, "not a tow_sim state");
  expectRefusal(withLine(good, "tow_sim_state", "tow_sim_state 3"), "format versions other than 1 and 2");
  expectRefusal(withLine(good, "heading", ""), "heading is missing");
  expectRefusal(good + "heading 1\n", "heading is given twice");
  expectRefusal(good + "colour 3\n", "colour is not a field");
  expectRefusal(withLine(good, "thrust", "thrust twelve"), "'twelve' is not a number");
  expectRefusal(withLine(good, "rudder", "rudder 0 0"), "rudder has 2 values, expected 3");
  expectRefusal(withLine(good, "y", "y 1 2 3"), "y has 3 values, expected 308");
  expectRefusal(withLine(good, "segments", "segments 0"), "segments must be a whole number in [1, 100000]");
  expectRefusal(withLine(good, "slack", "slack 2"), "slack: each flag must be 0 or 1");
  expectRefusal(withLine(good, "heading", "heading nan"), "tow_point and heading must be finite");
}

TEST(SavedState, AStateThatDoesNotFitTheRunIsRefusedWithNothingChanged)
{
  Scenario sc = shipped("turn_180");
  sc.duration = 10.0;
  sc.save_state_at = { 10.0 };
  const RunState saved = run(sc).states.at(10.0);

  auto ship = test::steamingShip(Eigen::Vector2d::Zero(), 0.0, 100);
  SimulationConfig other = sc.config;
  other.cable.segments = 20;  // the saved state has 50
  TowRun target(other, ship);
  target.start(5.0);
  const std::vector<double> before = target.simulator().stateVector();
  auto refuse = [&](const RunState& s, const std::string& words)
  {
    try
    {
      target.restore(s);
      ADD_FAILURE() << "accepted a state for: " << words;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(target.time(), 5.0);
    EXPECT_EQ(target.simulator().stateVector(), before);
  };
  refuse(saved, "50 segments and 300 m of cable out do not fit this cable (cable.segments 20");
  RunState bad = saved;
  bad.sim.segments = 20;
  refuse(bad, "y has 308 values; 20 segments need 128");
  SimulationConfig same = sc.config;
  TowRun fits(same, ship);
  fits.start(5.0);
  bad = saved;
  bad.sim.y[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fits.restore(bad), std::invalid_argument);
  bad = saved;
  bad.sim.winch_command = 0.2;
  EXPECT_THROW(fits.restore(bad), std::invalid_argument);  // no winch in turn_180
  bad = saved;
  bad.sim.y.back() = 0.3;  // a payout rate
  EXPECT_THROW(fits.restore(bad), std::invalid_argument);
  bad = saved;
  bad.sim.dt = 0.0;
  EXPECT_THROW(fits.restore(bad), std::invalid_argument);
  EXPECT_EQ(fits.time(), 5.0);
  EXPECT_NO_THROW(fits.restore(saved));
  EXPECT_EQ(fits.time(), saved.sim.t);
}

TEST(SavedState, EventsAtTheSaveTimeAreNotRepeatedWhenTheSimulatorStoppedShortOfIt)
{
  // The steppers may end 1e-12 s short of the target: a setpoint due at the save time has acted all the
  // same. Here one whose plan is unreachable (NaN) clears the winch's feed-forward base, which the tick at
  // the same time sets again: applied twice, the base would differ from the uninterrupted run's.
  Scenario sc = shipped("autopilot_winch");
  sc.duration = 30.0;
  sc.autopilot.setpoints = { { 10.0, false, 230.0 } };
  sc.save_state_at = { 10.0 };
  AutopilotLoop loop = sc.autopilot;
  loop.cable_out_plan = [](double, double) { return std::numeric_limits<double>::quiet_NaN(); };
  auto ship = std::make_shared<ShipHistory>(buildShipPath(sc));
  TowRun whole(sc.config, ship, sc.initial);
  whole.setAutopilot(loop);
  whole.start(0.0);
  whole.advanceTo(10.0);
  RunState saved = whole.saveState();
  saved.sim.t = 10.0 - 1e-12;  // as a stepper ending short of the target leaves it
  whole.advanceTo(10.5);
  TowRun restored(sc.config, ship, sc.initial);
  restored.setAutopilot(loop);
  restored.restore(saved);
  restored.advanceTo(10.5);
  ASSERT_TRUE(whole.saveState().autopilot && restored.saveState().autopilot);
  EXPECT_EQ(restored.saveState().autopilot->cable_out_base, whole.saveState().autopilot->cable_out_base);
  EXPECT_EQ(restored.saveState().autopilot->setpoint, 230.0);
  // A setpoint out of the autopilot's range is refused.
  RunState bad = whole.saveState();
  bad.autopilot->setpoint = 1e6;
  EXPECT_THROW(restored.restore(bad), std::invalid_argument);
}

TEST(SavedState, AStateFromAnotherShipPoseIsPlacedBehindTheScenariosShip)
{
  Scenario sc = shipped("turn_180");
  sc.duration = 100.0;
  sc.save_state_at = { 60.0 };
  const Output whole = run(sc);
  Scenario elsewhere = sc;
  elsewhere.save_state_at.clear();
  elsewhere.start_position += Eigen::Vector2d(1000.0, -500.0);
  elsewhere.initial.type = InitialShape::Type::kFile;
  elsewhere.initial.path = ::test::writeTempFile("saved_elsewhere.txt", runStateText(whole.states.at(60.0)));
  std::ostringstream series, shapes;
  BatchResult result;
  runScenario(elsewhere, series, shapes, result);
  EXPECT_NE(result.start_warning.find("placed behind it at t = 60 s"), std::string::npos) << result.start_warning;
  // The same tow relative to the ship: the layback (column 12) and depth (11) of the first row.
  auto cells = [](const std::string& row)
  {
    std::vector<double> v;
    std::istringstream in(row);
    std::string cell;
    while (std::getline(in, cell, ','))
      v.push_back(cell.empty() ? 0.0 : std::stod(cell));
    return v;
  };
  const std::vector<double> a = cells(from(whole.series, 60.0).front()), b = cells(lines(series.str()).front());
  EXPECT_NEAR(b[12], a[12], 1e-6);
  EXPECT_NEAR(b[11], a[11], 1e-6);
  EXPECT_NEAR(b[5] - b[1], a[5] - a[1], 1e-6);  // vehicle x relative to the ship
}

TEST(SavedState, ARelocatedStateTowsOnAsTheOriginalTurned)
{
  // A transient (an elevator step 2 s before the save), so the continuation is not a steady tow.
  SimulationConfig c;
  c.cable.segments = 20;
  CommandEvent step;
  step.t = 38.0;
  step.elevator = 0.3;
  TowRun original(c, test::steamingShip(Eigen::Vector2d::Zero(), 0.0, 400));
  original.schedule({ step });
  original.start(0.0);
  original.advanceTo(40.0);
  const RunState saved = original.saveState();
  const double depth_at_save = original.snapshot().depth;

  const double heading = 2.0;  // rad: the other ship steams north-west from elsewhere, 60 s later
  auto other_ship = test::steamingShip(Eigen::Vector2d(500.0, -300.0), heading, 400);
  TowRun moved(c, other_ship);
  moved.restore(relocate(saved, 100.0, other_ship->towPoint(100.0), heading));
  EXPECT_EQ(moved.time(), 100.0);
  EXPECT_NEAR(moved.simulator().data().actuators.elevator.angleAt(100.0),
              original.simulator().data().actuators.elevator.angleAt(40.0), 1e-15);

  original.advanceTo(70.0);
  moved.advanceTo(130.0);
  const TowSnapshot a = original.snapshot(), b = moved.snapshot();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3Xd rel_a = a.joints.colwise() - a.tow_point.p_W;
  const Eigen::Matrix3Xd rel_b = b.joints.colwise() - b.tow_point.p_W;
  EXPECT_LT((R * rel_a - rel_b).cwiseAbs().maxCoeff(), 1e-6 * rel_a.cwiseAbs().maxCoeff());
  EXPECT_NEAR(a.tension_ship, b.tension_ship, 1e-6 * a.tension_ship);
  EXPECT_NEAR(a.depth, b.depth, 1e-6);
  EXPECT_NEAR(std::remainder(b.yaw - a.yaw - heading, 2.0 * kPi), 0.0, 1e-6);
  // The comparison is of a moving state: the depth changed by more than 0.1 m (10^5 times the agreement asked).
  EXPECT_GT(std::abs(a.depth - depth_at_save), 0.1);
}

}  // namespace
}  // namespace tow_sim
