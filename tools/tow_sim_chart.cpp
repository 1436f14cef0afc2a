// tow_sim_chart: the towing chart of a configuration, the steady tow over a grid of ship speeds and lengths
// of cable out, without roscore.
//   tow_sim_chart --config FILE.yaml --speeds FROM:TO:STEP --cable-out FROM:TO:STEP
//                 [--current SPEED:DIRECTION_DEG] --out DIR [--no-plot]
//   tow_sim_chart --config FILE.yaml --target-depth D --speed U [--current ...]    the cable out for depth D
//   tow_sim_chart --config FILE.yaml --cable-out L --depth-band MIN:MAX [--current ...]   the speed window
// Writes DIR/chart.csv (docs/tools.md, "Towing charts") and, with python3-matplotlib, its PNG charts (tow_sim_plot);
// the planning forms print their answer. Exit codes: 0 done (chart points without an equilibrium are
// marked in the CSV, not an error); 2 bad arguments or configuration; 3 the depth or band is out of reach;
// 4 cannot write DIR.
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "cli.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/towing_chart.h"

#ifndef TOW_SIM_PLOT_SCRIPT
#define TOW_SIM_PLOT_SCRIPT ""
#endif

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_chart";
constexpr char kUsage[] =
    "tow_sim_chart --config FILE.yaml --speeds FROM:TO:STEP --cable-out FROM:TO:STEP\n"
    "                     [--current SPEED:DIRECTION_DEG] --out DIR [--no-plot]\n"
    "       tow_sim_chart --config FILE.yaml --target-depth D --speed U [--current SPEED:DIRECTION_DEG]\n"
    "       tow_sim_chart --config FILE.yaml --cable-out L --depth-band MIN:MAX\n"
    "                     [--current SPEED:DIRECTION_DEG]";
constexpr char kHelp[] = R"(
The towing chart of a configuration: the steady tow (depth, layback, tensions) over a grid of ship
speeds and lengths of cable out, without roscore. The second form finds the cable out that puts the
vehicle at a depth, the third the speeds that keep it in a depth band.

Options:
  --config FILE.yaml              the configuration, in the node's YAML format
                                  (config/tow_sim.yaml). Required.
  --speeds FROM:TO:STEP           the chart's ship speeds [m/s], each in [-15, 15]; one value is a
                                  grid of one.
  --cable-out FROM:TO:STEP        the chart's lengths of cable out [m], each in (0, 1e5]; with
                                  --depth-band, one length L [m].
  --out DIR                       the chart's output folder, made if it is missing.
  --no-plot                       writes only chart.csv, no PNG charts.
  --target-depth D                the depth [m] of the vehicle's CG to find the cable out for (with
                                  --speed), sought between winch.min_length and winch.max_length.
  --speed U                       the ship's speed [m/s] for --target-depth.
  --depth-band MIN:MAX            the vehicle's depth band [m] to find the speeds in [0.1, 10] m/s
                                  for (with --cable-out L).
  --current SPEED:DIRECTION_DEG   a uniform current of SPEED [m/s] in [-20, 20] flowing toward
                                  DIRECTION_DEG [deg] from the ship's heading, counter-clockwise (0:
                                  with the ship, 180: against it, 90: to port). Default: no current.
  -h, --help                      prints this help and exits.

Output: DIR/chart.csv (speed, cable_out, current, depth, layback, tension_ship, tension_vehicle,
ship_angle, max_tension, converged [m/s, m, m/s, m, m, N, N, deg, N, 0/1]) and, with
python3-matplotlib, its PNG charts in DIR (tow_sim_plot); see
docs/tools.md#towing-charts-tow_sim_chart. The planning forms print their answer on stdout and write
no file; they refuse the chart's --speeds, --out and --no-plot, and each option that takes one
number refuses a range.
Exit codes: 0 done (chart points without an equilibrium are blank in the CSV and said on stderr, not
an error); 2 bad arguments or configuration; 3 the depth or band is out of reach; 4 cannot write
DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

struct Options
{
  std::string config_path, speeds, cable_out, current, out_dir, target_depth, speed, depth_band;
  bool plot = true;
};

// Returns "" or what is wrong with the arguments.
std::string parseArguments(int argc, char** argv, Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--config") && has_value)
      o.config_path = argv[++i];
    else if (!std::strcmp(argv[i], "--speeds") && has_value)
      o.speeds = argv[++i];
    else if (!std::strcmp(argv[i], "--cable-out") && has_value)
      o.cable_out = argv[++i];
    else if (!std::strcmp(argv[i], "--current") && has_value)
      o.current = argv[++i];
    else if (!std::strcmp(argv[i], "--out") && has_value)
      o.out_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--target-depth") && has_value)
      o.target_depth = argv[++i];
    else if (!std::strcmp(argv[i], "--speed") && has_value)
      o.speed = argv[++i];
    else if (!std::strcmp(argv[i], "--depth-band") && has_value)
      o.depth_band = argv[++i];
    else if (!std::strcmp(argv[i], "--no-plot"))
      o.plot = false;
    else
      return tow_sim::cli::badArgument(kUsage, argc, argv, i);
  }
  if (o.config_path.empty())
    return "--config is needed";
  // Each form takes its own options: one the form would ignore is refused, not dropped.
  const bool planning = !o.target_depth.empty() || !o.depth_band.empty();
  if (planning && (!o.speeds.empty() || !o.out_dir.empty() || !o.plot))
    return "--speeds, --out and --no-plot belong to the chart; --target-depth and --depth-band print their "
           "answer and write no file";
  if (!o.target_depth.empty() && !o.depth_band.empty())
    return "give --target-depth (the cable out for a depth) or --depth-band (the speeds for a band), not both";
  if (!o.target_depth.empty())
  {
    if (!o.cable_out.empty())
      return "--target-depth finds the cable out: leave out --cable-out";
    return o.speed.empty() ? "--target-depth needs --speed" : "";
  }
  if (!o.depth_band.empty())
  {
    if (!o.speed.empty())
      return "--depth-band finds the speeds: leave out --speed";
    return o.cable_out.empty() ? "--depth-band needs --cable-out (one length)" : "";
  }
  if (!o.speed.empty())
    return "--speed belongs to --target-depth; a chart takes --speeds FROM:TO:STEP";
  if (o.speeds.empty() || o.cable_out.empty() || o.out_dir.empty())
    return "a chart needs --speeds, --cable-out and --out";
  return "";
}

// SPEED:DIRECTION_DEG: the current flowing toward DIRECTION_DEG from the ship's heading (+x), counter-clockwise.
Eigen::Vector3d currentFrom(const std::string& text)
{
  if (text.empty())
    return Eigen::Vector3d::Zero();
  const size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw std::invalid_argument("--current '" + text + "' must be SPEED:DIRECTION_DEG");
  const double speed = parseSingle(text.substr(0, colon), "--current speed");
  const double direction = parseSingle(text.substr(colon + 1), "--current direction") * tow_sim::kPi / 180.0;
  if (!(std::abs(speed) <= 20.0))
    throw std::invalid_argument("--current: " + std::to_string(speed) + " m/s is outside [-20, 20]");
  return speed * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
}

// tow_sim_plot beside this program (the install space's), else the source tree's; "" if neither is there.
std::string plotScript()
{
  struct stat st;
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (n > 0)
  {
    std::string beside(self, static_cast<size_t>(n));
    beside = beside.substr(0, beside.rfind('/') + 1) + "tow_sim_plot";
    if (stat(beside.c_str(), &st) == 0)
      return beside;
  }
  const std::string source = TOW_SIM_PLOT_SCRIPT;
  return !source.empty() && stat(source.c_str(), &st) == 0 ? source : "";
}

// Draws the charts with tow_sim_plot when it is there.
void plotChart(const std::string& out_dir)
{
  const std::string script = plotScript();
  if (script.empty())
  {
    std::printf("tow_sim_chart: draw the charts with tow_sim_plot %s\n", out_dir.c_str());
    return;
  }
  const std::string command = "/usr/bin/python3 '" + script + "' '" + out_dir + "'";
  if (std::system(command.c_str()) != 0)
    std::fprintf(stderr, "tow_sim_chart: the charts were not drawn (is python3-matplotlib installed?)\n");
}
// --target-depth D --speed U: the cable out, within the winch's limits.
int planDepth(const SimulationConfig& config, const Options& o, const Eigen::Vector3d& current)
{
  const double depth = parseSingle(o.target_depth, "--target-depth"), speed = parseSingle(o.speed, "--speed");
  const CableOutPlan plan =
      planCableOut(config, depth, speed, current, config.winch.min_length, config.winch.max_length);
  if (!plan.reachable)
  {
    std::printf("tow_sim_chart: unreachable: %s\n", plan.reason.c_str());
    return 3;
  }
  const ChartPoint& p = plan.point;
  std::printf(
      "tow_sim_chart: %.2f m out puts the vehicle at %.2f m at %g m/s: layback %.1f m, tension at the ship "
      "%.0f N, at the vehicle %.0f N, largest %.0f N\n",
      plan.cable_out, p.depth, speed, p.layback, p.tension_ship, p.tension_vehicle, p.max_tension);
  return 0;
}

// --cable-out L --depth-band MIN:MAX: the speed window.
int planSpeeds(const SimulationConfig& config, const Options& o, const Eigen::Vector3d& current)
{
  const double cable_out = parseSingle(o.cable_out, "--cable-out");
  const size_t colon = o.depth_band.find(':');
  if (colon == std::string::npos)
    throw std::invalid_argument("--depth-band '" + o.depth_band + "' must be MIN:MAX [m]");
  const double lo = parseSingle(o.depth_band.substr(0, colon), "--depth-band"),
               hi = parseSingle(o.depth_band.substr(colon + 1), "--depth-band");
  if (!(lo < hi))
    throw std::invalid_argument("--depth-band '" + o.depth_band + "': MIN must be below MAX");
  const SpeedWindow w = speedWindow(config, cable_out, lo, hi, current);
  if (!w.found)
  {
    std::printf("tow_sim_chart: unreachable: %s\n", w.reason.c_str());
    return 3;
  }
  std::printf("tow_sim_chart: with %g m out the vehicle stays between %g and %g m from %.3f to %.3f m/s\n", cable_out,
              lo, hi, w.slowest, w.fastest);
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  Options o;
  const std::string wrong = parseArguments(argc, argv, o);
  if (!wrong.empty())
    return usage(wrong);
  SimulationConfig config;
  std::vector<double> speeds, cable_outs;
  Eigen::Vector3d current;
  try
  {
    config = loadConfigFile(o.config_path);
    if (!o.target_depth.empty() || !o.depth_band.empty())
    {
      current = currentFrom(o.current);
      return o.target_depth.empty() ? planSpeeds(config, o, current) : planDepth(config, o, current);
    }
    speeds = parseRange(o.speeds, "--speeds");
    cable_outs = parseRange(o.cable_out, "--cable-out");
    for (double s : speeds)
      if (!(std::abs(s) <= 15.0))
        throw std::invalid_argument("--speeds: " + std::to_string(s) + " m/s is outside [-15, 15]");
    for (double l : cable_outs)
      if (!(l > 0.0 && l <= 1e5))
        throw std::invalid_argument("--cable-out: " + std::to_string(l) + " m is outside (0, 1e5]");
    current = currentFrom(o.current);
  }
  catch (const std::exception& e)
  {
    return usage(e.what());
  }
  std::error_code made;  // with its parents (out/chart); a failure shows as the file not opening
  std::filesystem::create_directories(o.out_dir, made);
  const std::string csv = o.out_dir + "/chart.csv";
  std::ofstream out(csv);
  if (!out)
  {
    std::fprintf(stderr, "tow_sim_chart: cannot write %s\n", csv.c_str());
    return 4;
  }
  out << chartHeader() << '\n';
  int failed = 0;
  for (const ChartPoint& p : towingChart(config, speeds, cable_outs, current))
  {
    writeChartRow(out, p);
    if (!p.converged && ++failed)
      std::fprintf(stderr, "tow_sim_chart: no equilibrium at %g m/s, %g m: %s\n", p.speed, p.cable_out,
                   p.error.c_str());
  }
  out.close();
  std::printf("tow_sim_chart: %zu points (%d without an equilibrium) in %s\n", speeds.size() * cable_outs.size(),
              failed, csv.c_str());
  if (o.plot)
    plotChart(o.out_dir);
  return 0;
}
