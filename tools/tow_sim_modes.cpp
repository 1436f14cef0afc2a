// tow_sim_modes: the natural periods and mode shapes of a configuration's steady tow, without roscore.
//   tow_sim_modes --config FILE.yaml --speed U [--cable-out L] [--count N] [--out DIR]
// Prints the first N modes (default 10) and, with --out, writes DIR/modes.csv (index, period [s], frequency
// [rad/s], damping_ratio, dominant) and DIR/mode_shapes.csv (mode, joint, dx, dy, dz: the joints' displacements,
// the largest 1) for those modes (docs/tools.md, "Natural modes"). Exit codes: 0 done;
// 2 bad arguments or configuration; 3 no steady tow found; 4 cannot write DIR.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli.h"
#include "tow_sim/scenario/towing_chart.h"

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_modes";
constexpr char kUsage[] = "tow_sim_modes --config FILE.yaml --speed U [--cable-out L] [--count N] [--out DIR]";
constexpr char kHelp[] = R"(
The natural periods, damping ratios and mode shapes of a configuration's steady tow, without
roscore.

Options:
  --config FILE.yaml   the configuration, in the node's YAML format (config/tow_sim.yaml). Required.
  --speed U            the ship's speed [m/s], a number in [-20, 20]. Required.
  --cable-out L        the length of cable out [m], a number in [1e-3, 1e5] (default the
                       configuration's cable.length).
  --count N            how many modes to print and write, the lowest frequency first, a number in
                       [1, 1e6] (default 10).
  --out DIR            the output folder, made if it is missing (default: no files, the table only).
  -h, --help           prints this help and exits.

Output: a table of the first N modes on stdout (period [s], frequency [rad/s], damping ratio,
dominant motion); with --out, DIR/modes.csv (index, period [s], frequency [rad/s], damping_ratio,
dominant) and DIR/mode_shapes.csv (mode, joint, dx, dy, dz: the joints' displacements, the largest
1); see docs/tools.md#natural-modes-tow_sim_modes.
Exit codes: 0 done; 2 bad arguments or configuration; 3 no steady tow found; 4 cannot write DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

double number(const char* text, const std::string& option, double low, double high)
{
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (*end != '\0' || !(v >= low && v <= high))
    throw std::invalid_argument(option + " " + text + ": a number in [" + std::to_string(low) + ", " +
                                std::to_string(high) + "]");
  return v;
}

int write(const std::string& dir, const std::vector<Mode>& modes, size_t count)
{
  std::error_code made;
  std::filesystem::create_directories(dir, made);
  std::ofstream table(dir + "/modes.csv"), shapes(dir + "/mode_shapes.csv");
  if (!table || !shapes)
  {
    std::fprintf(stderr, "tow_sim_modes: cannot write into %s\n", dir.c_str());
    return 4;
  }
  table.precision(10);
  shapes.precision(10);
  table << "index,period,frequency,damping_ratio,dominant\n";
  shapes << "mode,joint,dx,dy,dz\n";
  for (size_t i = 0; i < count; ++i)
  {
    const Mode& m = modes[i];
    table << i + 1 << ',' << m.period << ',' << m.frequency << ',' << m.damping_ratio << ',' << m.dominant << '\n';
    for (Eigen::Index j = 0; j < m.shape.cols(); ++j)  // joints x_2 .. x_{nu+2}
      shapes << i + 1 << ',' << j + 2 << ',' << m.shape(0, j) << ',' << m.shape(1, j) << ',' << m.shape(2, j) << '\n';
  }
  std::printf("tow_sim_modes: wrote %s/modes.csv and mode_shapes.csv\n", dir.c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  std::string config_path, out_dir;
  const char *speed = nullptr, *cable_out = nullptr, *count = nullptr;
  for (int i = 1; i < argc; ++i)
  {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--config") && has_value)
      config_path = argv[++i];
    else if (!std::strcmp(argv[i], "--speed") && has_value)
      speed = argv[++i];
    else if (!std::strcmp(argv[i], "--cable-out") && has_value)
      cable_out = argv[++i];
    else if (!std::strcmp(argv[i], "--count") && has_value)
      count = argv[++i];
    else if (!std::strcmp(argv[i], "--out") && has_value)
      out_dir = argv[++i];
    else
      return usage(tow_sim::cli::badArgument(kUsage, argc, argv, i));
  }
  if (config_path.empty() || !speed)
    return usage("--config and --speed are needed");
  std::vector<Mode> modes;
  size_t n = 10;
  try
  {
    const SimulationConfig config = loadConfigFile(config_path);
    const double u = number(speed, "--speed", -20.0, 20.0);
    const double l = cable_out ? number(cable_out, "--cable-out", 1e-3, 1e5) : config.cable.length;
    n = count ? static_cast<size_t>(number(count, "--count", 1.0, 1e6)) : n;
    modes = steadyTowModes(config, u, l, Eigen::Vector3d::Zero(), n);  // the n lowest, O(nu) per iteration
  }
  catch (const std::invalid_argument& e)
  {
    return usage(e.what());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_modes: no steady tow: %s\n", e.what());
    return 3;
  }
  n = std::min(n, modes.size());
  std::printf("%5s %12s %14s %14s  %s\n", "mode", "period [s]", "omega [rad/s]", "damping ratio", "dominant");
  for (size_t i = 0; i < n; ++i)
    std::printf("%5zu %12.4f %14.6f %14.6f  %s\n", i + 1, modes[i].period, modes[i].frequency, modes[i].damping_ratio,
                modes[i].dominant.c_str());
  return out_dir.empty() ? 0 : write(out_dir, modes, n);
}
