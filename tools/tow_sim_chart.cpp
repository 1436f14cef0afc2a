// tow_sim_chart: the towing chart of a configuration, the steady tow over a grid of ship speeds and lengths
// of cable out, without roscore.
//   tow_sim_chart --config FILE.yaml --speeds FROM:TO:STEP --cable-out FROM:TO:STEP
//                 [--current SPEED:DIRECTION_DEG] --out DIR [--no-plot]
// Writes DIR/chart.csv (README, Towing charts) and, with python3-matplotlib, its PNG charts (tow_sim_plot).
// Exit codes: 0 done (points without an equilibrium are marked in the CSV, not an error); 2 bad arguments
// or configuration; 4 cannot write DIR.
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "tow_sim/scenario/towing_chart.h"

#ifndef TOW_SIM_PLOT_SCRIPT
#define TOW_SIM_PLOT_SCRIPT ""
#endif

namespace
{
using namespace tow_sim;
constexpr double kPi = 3.14159265358979323846;

int usage(const std::string& why)
{
  std::fprintf(stderr,
               "tow_sim_chart: %s\nusage: tow_sim_chart --config FILE.yaml --speeds FROM:TO:STEP --cable-out "
               "FROM:TO:STEP [--current SPEED:DIRECTION_DEG] --out DIR [--no-plot]\n",
               why.c_str());
  return 2;
}

struct Options
{
  std::string config_path, speeds, cable_out, current, out_dir;
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
    else if (!std::strcmp(argv[i], "--no-plot"))
      o.plot = false;
    else
      return std::string("unknown argument '") + argv[i] + "'";
  }
  if (o.config_path.empty() || o.speeds.empty() || o.cable_out.empty() || o.out_dir.empty())
    return "--config, --speeds, --cable-out and --out are needed";
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
  const double speed = parseRange(text.substr(0, colon), "--current speed").at(0);
  const double direction = parseRange(text.substr(colon + 1), "--current direction").at(0) * kPi / 180.0;
  if (!(std::abs(speed) <= 20.0))
    throw std::invalid_argument("--current: " + std::to_string(speed) + " m/s is outside [-20, 20]");
  return speed * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
}

// Draws the charts with tow_sim_plot (the source tree's) when it is there.
void plotChart(const std::string& out_dir)
{
  const std::string script = TOW_SIM_PLOT_SCRIPT;
  struct stat st;
  if (script.empty() || stat(script.c_str(), &st) != 0)
  {
    std::printf("tow_sim_chart: draw the charts with tow_sim_plot %s\n", out_dir.c_str());
    return;
  }
  const std::string command = "/usr/bin/python3 '" + script + "' '" + out_dir + "'";
  if (std::system(command.c_str()) != 0)
    std::fprintf(stderr, "tow_sim_chart: the charts were not drawn (is python3-matplotlib installed?)\n");
}
}  // namespace

int main(int argc, char** argv)
{
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
  mkdir(o.out_dir.c_str(), 0755);
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
