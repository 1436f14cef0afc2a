// The offline runner and its scenarios: every shipped scenario runs and writes the documented CSV
// columns, finite, with the expected number of rows; bad scenarios are refused naming the key; the
// plot command makes non-empty PNGs; the ship path follows its manoeuvres.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace
{

std::string run(const std::string& command, int* status)
{
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string out;
  char buffer[512];
  while (pipe && fgets(buffer, sizeof(buffer), pipe))
    out += buffer;
  const int raw = pipe ? pclose(pipe) : -1;
  *status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

std::vector<std::vector<std::string>> readCsv(const std::string& path)
{
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
  {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
      cells.push_back(cell);
    if (!line.empty() && line.back() == ',')
      cells.push_back("");  // a blank last cell
    rows.push_back(cells);
  }
  return rows;
}

long fileSize(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0 ? static_cast<long>(st.st_size) : -1;
}

// A fresh folder for this test process's outputs, so no test reads files an earlier run left behind.
const std::string& outputRoot()
{
  static const std::string root = []
  {
    char pattern[] = "/tmp/tow_sim_test_batch_XXXXXX";
    const char* made = mkdtemp(pattern);
    return std::string(made ? made : "");
  }();
  return root;
}

// Every scenario in scenarios/ (the bathymetry files there are grids, not scenarios).
const char* const kShippedScenarios[] = {
  "report_elevator_step", "turn_180",       "speed_change",    "zigzag",
  "winch_payout",         "seabed_shoal",   "sheared_current", "autopilot_depth_turn",
  "autopilot_terrain",    "head_seas",      "autopilot_winch", "heave_snap",
  "two_part_tow",         "rolling_towfish"
};

// Runs a shipped scenario once per test process (whichever test asks first), in this process through the
// batch library (runScenario, what tow_sim_batch calls), writing its CSV files into the output folder for
// the checks and the plot command; status 0, or 3 with the error when the run stopped.
struct ScenarioRun
{
  std::string out, log;
  int status = -1;
};
const ScenarioRun& shippedRun(const std::string& name)
{
  static std::map<std::string, ScenarioRun> runs;
  auto found = runs.find(name);
  if (found != runs.end())
    return found->second;
  ScenarioRun& r = runs[name];
  r.out = outputRoot() + "/" + name;
  mkdir(r.out.c_str(), 0755);
  const Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
  std::ofstream series(r.out + "/timeseries.csv"), shapes(r.out + "/shapes.csv");
  std::ofstream(r.out + "/scenario.yaml") << toYaml(sc) << "\n";
  BatchResult result;
  try
  {
    runScenario(sc, series, shapes, result);
    r.status = 0;
  }
  catch (const std::exception& e)
  {
    r.status = 3;
    r.log = e.what();
  }
  r.log += result.start_warning;
  return r;
}

// The time series of a shipped scenario, run if it has not been yet; fails the test if it is missing.
std::vector<std::vector<std::string>> timeseries(const std::string& name)
{
  const ScenarioRun& r = shippedRun(name);
  EXPECT_EQ(r.status, 0) << r.log;
  const std::string path = r.out + "/timeseries.csv";
  EXPECT_GT(fileSize(path), 0) << path;
  return readCsv(path);
}

// timeseries.csv's columns, as docs/tools.md ("Output files") documents them.
const std::vector<std::string> kColumns = { "t",
                                            "ship_x",
                                            "ship_y",
                                            "ship_z",
                                            "ship_speed",
                                            "vehicle_x",
                                            "vehicle_y",
                                            "vehicle_z",
                                            "vehicle_roll",
                                            "vehicle_pitch",
                                            "vehicle_yaw",
                                            "depth",
                                            "layback",
                                            "diversion",
                                            "diversion_rate",
                                            "tension_ship",
                                            "tension_vehicle",
                                            "rudder",
                                            "elevator",
                                            "thrust",
                                            "max_length_error",
                                            "cable_length",
                                            "payout_rate",
                                            "vehicle_altitude",
                                            "seabed_contacts",
                                            "depth_setpoint",
                                            "tension_ship_min",
                                            "tension_ship_max",
                                            "tension_vehicle_min",
                                            "tension_vehicle_max",
                                            "snap_count",
                                            "max_strain" };

// The documented columns, and five for each point body (docs/tools.md, "Output files").
std::vector<std::string> columnsOf(const Scenario& sc)
{
  std::vector<std::string> columns = kColumns;
  for (size_t i = 1; i <= sc.config.bodies.size(); ++i)
    for (const char* column : { "_x", "_y", "_depth", "_tension_above", "_tension_below" })
      columns.push_back("body" + std::to_string(i) + column);
  return columns;
}

// Every cell of every row finite (blank only where documented), and each output's interval extremes
// bracketing its tension.
void expectRowsFinite(const std::string& name, const Scenario& sc, const std::vector<std::vector<std::string>>& rows)
{
  const std::vector<std::string> columns = columnsOf(sc);
  for (size_t r = 1; r < rows.size(); ++r)
  {
    ASSERT_EQ(rows[r].size(), columns.size()) << name << " row " << r;
    for (size_t c = 0; c < rows[r].size(); ++c)
    {
      const std::string& cell = rows[r][c];
      if (cell.empty() && columns[c] == "vehicle_altitude" && sc.config.seabed.type == SeabedParams::Type::kNone)
        continue;  // documented: blank without a seabed
      if (cell.empty() && columns[c] == "depth_setpoint" && !sc.autopilot.enabled)
        continue;  // and without an autopilot
      ASSERT_TRUE(std::isfinite(std::stod(cell))) << name << " row " << r << " column " << columns[c];
    }
    // The interval's extremes bracket the tension at the output time.
    for (const auto& [value, lo, hi] : { std::tuple<int, int, int>{ 15, 26, 27 }, { 16, 28, 29 } })
    {
      const double v = std::stod(rows[r][static_cast<size_t>(value)]);
      ASSERT_LE(std::stod(rows[r][static_cast<size_t>(lo)]), v) << name << " row " << r;
      ASSERT_GE(std::stod(rows[r][static_cast<size_t>(hi)]), v) << name << " row " << r;
    }
  }
}

// tow_sim_plot makes the documented plots of a run's folder, and only those that apply to the scenario.
void expectPlots(const std::string& name, const Scenario& sc, const std::string& out)
{
  int status = 0;
  const std::string plot_log =
      run(std::string("/usr/bin/python3 ") + TOW_SIM_SOURCE_DIR + "/scripts/tow_sim_plot " + out, &status);
  ASSERT_EQ(status, 0) << plot_log;
  for (const char* png : { "depth_diversion.png", "tensions.png", "plan_view.png", "side_view.png" })
    EXPECT_GT(fileSize(out + "/" + png), 5000) << name << " " << png;
  EXPECT_EQ(fileSize(out + "/winch.png") > 5000, sc.config.winch.enabled) << name;
  EXPECT_EQ(fileSize(out + "/seabed.png") > 5000, sc.config.seabed.type != SeabedParams::Type::kNone) << name;
  const bool heaves = sc.config.environment.waves.type != WaveParams::Type::kNone || !sc.motion_file.empty();
  EXPECT_EQ(fileSize(out + "/waves.png") > 5000, heaves) << name;
  EXPECT_EQ(fileSize(out + "/snaps.png") > 5000, sc.config.cable.elastic()) << name;
  EXPECT_EQ(fileSize(out + "/bodies.png") > 5000, !sc.config.bodies.empty()) << name;
}

TEST(Batch, EveryScenarioRunsAndWritesTheDocumentedColumns)
{
  for (const std::string name : kShippedScenarios)
  {
    ASSERT_FALSE(outputRoot().empty()) << "cannot make a temporary folder";
    const std::string scenario = std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
    const ScenarioRun& r = shippedRun(name);
    ASSERT_EQ(r.status, 0) << r.log;
    const std::string& out = r.out;
    const Scenario sc = loadScenarioFile(scenario);
    const auto rows = readCsv(out + "/timeseries.csv");
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows[0], columnsOf(sc)) << name;
    EXPECT_EQ(rows.size(), static_cast<size_t>(std::lround(sc.duration / sc.output_interval)) + 2) << name;
    expectRowsFinite(name, sc, rows);
    // Tension is positive, the vehicle is under water, the lengths held: a step leaves a relative length
    // error (before projection) of the order of the stepper's tolerance.
    const NumericsParams& num = sc.config.numerics;
    const double length_bound = isImplicit(num.stepper) ? 5.0 * num.implicit_rel_tol : 10.0 * num.rel_tol;
    for (size_t r = 1; r < rows.size(); ++r)
    {
      EXPECT_GT(std::stod(rows[r][15]), 0.0);
      EXPECT_GT(std::stod(rows[r][11]), 0.0);
      EXPECT_LT(std::stod(rows[r][20]), length_bound) << name << " row " << r;
    }
    const auto shapes = readCsv(out + "/shapes.csv");
    std::vector<std::string> shape_columns = { "t", "joint", "x", "y", "z", "tension", "slack" };
    if (!sc.config.sections.empty())
      shape_columns.push_back("section");
    EXPECT_EQ(shapes[0], shape_columns) << name;
    if (!sc.config.winch.enabled)  // else the joint count changes
    {
      EXPECT_EQ((shapes.size() - 1) % static_cast<size_t>(sc.config.cable.segments + 2), 0u);
    }
    // The resolved scenario reads back to the same run.
    const Scenario again = loadScenarioFile(out + "/scenario.yaml");
    EXPECT_EQ(again.duration, sc.duration);
    EXPECT_EQ(again.manoeuvres.size(), sc.manoeuvres.size());
    expectPlots(name, sc, out);
  }
}

TEST(Batch, ReportsScenarioEffectsWithTheRightSense)
{
  // The shipped scenarios (run here unless an earlier test of this process ran them, into this process's
  // own folder): the elevator step raised the vehicle, the slow-down sank it (and, with less drag holding
  // the cable up, the ship carries more of its weight), the port turn carried it to port.
  ASSERT_FALSE(outputRoot().empty()) << "cannot make a temporary folder";
  for (const char* name : { "report_elevator_step", "speed_change", "turn_180", "winch_payout", "seabed_shoal",
                            "sheared_current", "autopilot_depth_turn", "autopilot_terrain" })
    ASSERT_GT(timeseries(name).size(), 100u) << name;
  auto column = [](const std::string& name, int c, int row)
  {
    const auto rows = timeseries(name);
    return std::stod(
        rows[static_cast<size_t>(row < 0 ? static_cast<int>(rows.size()) + row : row)][static_cast<size_t>(c)]);
  };
  EXPECT_LT(column("report_elevator_step", 11, -1), column("report_elevator_step", 11, 60) - 0.2);
  EXPECT_GT(column("speed_change", 11, -1), column("speed_change", 11, 50) + 20.0);
  EXPECT_GT(column("speed_change", 15, -1), column("speed_change", 15, 50));
  EXPECT_GT(column("turn_180", 13, 250), 50.0);
  // Winch: out to 450 m and the vehicle deeper there, back to 300 m and the depth with it.
  EXPECT_NEAR(column("winch_payout", 21, 500), 450.0, 0.01);
  EXPECT_NEAR(column("winch_payout", 21, -1), 300.0, 0.01);
  EXPECT_GT(column("winch_payout", 11, 500), column("winch_payout", 11, 50) + 20.0);
  EXPECT_NEAR(column("winch_payout", 11, -1), column("winch_payout", 11, 50), 0.1);
  // Seabed: never more than a penalty's centimetres into it, and on the 70 m shoal at the end.
  const auto shoal = timeseries("seabed_shoal");
  for (size_t r = 1; r < shoal.size(); ++r)
    EXPECT_GT(std::stod(shoal[r][23]), -0.3) << "row " << r;
  EXPECT_LT(column("seabed_shoal", 11, -1), 70.5);
  EXPECT_GT(column("seabed_shoal", 24, -1), 0.0);  // the cable drags on the bottom
  // Sheared cross-current from the south: the vehicle is carried to port of the eastbound ship.
  EXPECT_GT(column("sheared_current", 13, 250), 5.0);
  // The autopilot in the loop, offline: 20 m up within 60 s of the step and held within 1 m through the
  // turn (the rostest of depth_autopilot_node checks the same through ROS); 25 m over the ridge.
  const auto turn = timeseries("autopilot_depth_turn");
  double worst = 0.0;
  for (size_t r = 161; r < turn.size(); ++r)
    worst = std::max(worst, std::abs(std::stod(turn[r][11]) - 221.8));
  const auto ridge = timeseries("autopilot_terrain");
  double lowest = 1e9, highest = 0.0;
  for (size_t r = 101; r < ridge.size(); ++r)
  {
    lowest = std::min(lowest, std::stod(ridge[r][23]));
    highest = std::max(highest, std::stod(ridge[r][23]));
  }
  std::printf(
      "autopilot offline: depth error from 60 s after the step through the turn <= %.2f m; altitude over "
      "the ridge %.2f .. %.2f m (setpoint 25 m)\n",
      worst, lowest, highest);
  EXPECT_LT(worst, 1.0);
  EXPECT_GT(lowest, 22.0);
  EXPECT_LT(highest, 28.0);
  EXPECT_GT(column("autopilot_terrain", 11, 200) - column("autopilot_terrain", 11, 800), 30.0);  // it climbed
}

// Largest difference between two CSV files of the same columns, each column measured against its own
// scale (its largest |value| in `expected`, at least 1): blank cells must stay blank, rows and header equal.
double largestScaledDifference(const std::vector<std::vector<std::string>>& actual,
                               const std::vector<std::vector<std::string>>& expected, std::string* where)
{
  if (actual.size() != expected.size() || actual.empty() || actual[0] != expected[0])
  {
    *where = "header or row count (" + std::to_string(actual.size()) + " rows, expected " +
             std::to_string(expected.size()) + ")";
    return INFINITY;
  }
  const size_t columns = expected[0].size();
  std::vector<double> scale(columns, 1.0);
  for (size_t r = 1; r < expected.size(); ++r)
    for (size_t c = 0; c < columns && c < expected[r].size(); ++c)
      if (!expected[r][c].empty())
        scale[c] = std::max(scale[c], std::abs(std::stod(expected[r][c])));
  double worst = 0.0;
  for (size_t r = 1; r < expected.size(); ++r)
  {
    if (actual[r].size() != expected[r].size())
    {
      *where = "row " + std::to_string(r) + " has " + std::to_string(actual[r].size()) + " cells";
      return INFINITY;
    }
    for (size_t c = 0; c < columns; ++c)
    {
      const std::string &a = actual[r][c], &e = expected[r][c];
      const double difference = a.empty() || e.empty() ? (a.empty() == e.empty() ? 0.0 : INFINITY)
                                                       : std::abs(std::stod(a) - std::stod(e)) / scale[c];
      if (difference > worst)
      {
        worst = difference;
        *where = "row " + std::to_string(r) + ", column " + expected[0][c] + ": " + a + " vs " + e;
      }
    }
  }
  return worst;
}

// The outputs recorded in test/golden/ (scripts/record_golden.sh) before a refactor: every shipped scenario
// must reproduce them to 1e-9 of each column's scale, unless a change meant to move them re-records them.
TEST(Batch, ShippedScenariosReproduceTheGoldenOutputs)
{
  ASSERT_FALSE(outputRoot().empty()) << "cannot make a temporary folder";
  for (const std::string name : kShippedScenarios)
    for (const char* file : { "timeseries.csv", "shapes.csv" })
    {
      const ScenarioRun& r = shippedRun(name);
      ASSERT_EQ(r.status, 0) << r.log;
      const std::string golden = std::string(TOW_SIM_SOURCE_DIR) + "/test/golden/" + name + "/" + file;
      ASSERT_GT(fileSize(golden), 0) << golden;
      std::string where;
      const double difference = largestScaledDifference(readCsv(r.out + "/" + file), readCsv(golden), &where);
      std::printf("golden %s/%s: largest difference %.2e of the column's scale\n", name.c_str(), file, difference);
      EXPECT_LE(difference, 1e-9) << name << "/" << file << ": " << where;
    }
}

// The tool is a thin adapter: its files are the library's run, byte for byte, plus scenario.yaml.
TEST(Batch, TheToolWritesWhatTheLibraryRuns)
{
  ASSERT_FALSE(outputRoot().empty()) << "cannot make a temporary folder";
  const ScenarioRun& in_process = shippedRun("report_elevator_step");
  ASSERT_EQ(in_process.status, 0) << in_process.log;
  const std::string out = outputRoot() + "/tool_report_elevator_step";
  int status = -1;
  const std::string log = run(std::string(TOW_SIM_BATCH_BINARY) + " --scenario " + TOW_SIM_SOURCE_DIR +
                                  "/scenarios/report_elevator_step.yaml --out " + out,
                              &status);
  ASSERT_EQ(status, 0) << log;
  for (const char* file : { "timeseries.csv", "shapes.csv" })
  {
    std::ifstream a(out + "/" + file), b(in_process.out + "/" + file);
    const std::string tool((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
    const std::string library((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    EXPECT_FALSE(tool.empty()) << file;
    EXPECT_TRUE(tool == library) << file;
  }
  EXPECT_EQ(loadScenarioFile(out + "/scenario.yaml").duration, 400.0);
}

TEST(Batch, BadScenariosAreRefusedNamingTheKey)
{
  ASSERT_FALSE(outputRoot().empty()) << "cannot make a temporary folder";
  const std::string path = outputRoot() + "/bad_scenario.yaml";
  auto refuse = [&](const std::string& yaml, const std::string& needle)
  {
    std::ofstream(path) << yaml;
    int status = 0;
    const std::string log =
        run(std::string(TOW_SIM_BATCH_BINARY) + " --scenario " + path + " --out " + outputRoot() + "/bad", &status);
    EXPECT_EQ(status, 2) << yaml;
    EXPECT_NE(log.find(needle), std::string::npos) << log;
  };
  refuse("", "scenario: must be a mapping");  // an empty file used to run a default scenario
  refuse("[1, 2, 3]", "scenario: must be a mapping");
  refuse("ship: {manoeuvres: [{type: loop}]}", "ship.manoeuvres[0].type: 'loop' must be");
  refuse("ship: {manoeuvres: [{type: turn, radius: 1}]}", "ship.manoeuvres[0].radius = 1 is out of range");
  refuse("simulation: {duration: -5}", "simulation.duration = -5");
  refuse("comands: []", "scenario.comands: unknown key");
  refuse("commands: [{t: 5, elevator: 3}]", "commands[0].elevator = 3");
  refuse("cable: {segments: 0}", "cable.segments = 0");
  refuse("initial_state: {type: points, points: [1, 2, 3]}", "initial_state.points: must hold");
  refuse("initial_state: {type: line, direction: [1e7, 0, 0]}", "scenario.initial_state.direction[0] = 10000000");
  refuse("commands: [{t: 5, payout_rate: 1}]", "commands[0].payout_rate: needs the winch");
  refuse("winch: {enabled: true, max_length: 100}", "cable.length = 500 is out of range");
  refuse("seabed: {type: grid, grid_file: no_such_grid.yaml}",
         "seabed.grid_file: " + outputRoot() + "/no_such_grid.yaml");
  refuse("seabed: {type: flat, depth: -3}", "seabed.depth = -3");
  refuse("environment: {current_profile: [{depth: 50}, {depth: 20}]}", "current_profile[1].depth = 20");
  refuse("autopilot: {kp: -1}", "autopilot.kp = -1");
  refuse("autopilot: {max_depth: -5, setpoints: [{t: 0, depth: 10}]}", "autopilot.max_depth = -5");
  refuse("autopilot: {setpoints: [{t: 0, altitude: 10}]}", "autopilot.setpoints[0].altitude: needs a seabed");
  refuse("autopilot: {}\ncommands: [{t: 5, elevator: 0.1}]", "commands[0]: rudder, elevator and thrust belong");
  refuse("simulation: {output_interval: 1, save_state_at: [10.5]}", "simulation.save_state_at: must list output times");
  refuse("simulation: {duration: 50, save_state_at: [60]}", "simulation.save_state_at: must list output times");
  refuse("initial_state: {type: file}", "initial_state.path: is the saved state of type: file");
  refuse("initial_state: {type: file, path: no_such_state.txt}",
         "initial_state.path: cannot read " + outputRoot() + "/no_such_state.txt");
  std::ofstream(outputRoot() + "/not_a_state.txt") << "t 5\n";
  refuse("initial_state: {type: file, path: not_a_state.txt}", "bad initial state: initial_state.path " + outputRoot());
  int status = 0;
  run(std::string(TOW_SIM_BATCH_BINARY) + " --scenario", &status);
  EXPECT_EQ(status, 2);
}

}  // namespace
}  // namespace tow_sim
