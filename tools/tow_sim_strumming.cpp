// tow_sim_strumming: where a configuration's steady tow sheds vortices and which string modes of its cable that
// shedding can lock into (docs/physics.md §13), without roscore.
//   tow_sim_strumming --config FILE.yaml --speed U [--cable-out L] [--current SPEED:DIRECTION_DEG]
//                     [--bandwidth B] [--out DIR]
// Prints each span's (the cable between point bodies) fundamental, the modes its cable can lock into and the
// dominant one; with --out writes DIR/strumming.csv (a row per cable segment) and DIR/strumming_spans.csv
// (docs/tools.md, "Strumming"). Exit codes: 0 done; 2 bad arguments or configuration; 3 no steady tow found;
// 4 cannot write DIR.
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

#include "cli.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/towing_chart.h"

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_strumming";
constexpr char kUsage[] =
    "tow_sim_strumming --config FILE.yaml --speed U [--cable-out L]\n"
    "                         [--current SPEED:DIRECTION_DEG] [--bandwidth B] [--out DIR]";
constexpr char kHelp[] = R"(
Where a configuration's steady tow sheds vortices and which string modes of its cable that shedding
can lock into (docs/physics.md section 13), without roscore.

Options:
  --config FILE.yaml              the configuration, in the node's YAML format
                                  (config/tow_sim.yaml). Required.
  --speed U                       the ship's speed [m/s], a number in [-20, 20]. Required.
  --cable-out L                   the length of cable out [m], a number in [1e-3, 1e5] (default the
                                  configuration's cable.length).
  --current SPEED:DIRECTION_DEG   a uniform current of SPEED [m/s] in [-20, 20] flowing toward
                                  DIRECTION_DEG [deg] in [-360, 360] from the ship's heading,
                                  counter-clockwise. Default: no current.
  --bandwidth B                   the lock-in band's half width as a fraction of the shedding
                                  frequency, a number in [0, 1) (default 0.2: a mode locks in within
                                  +-20 %).
  --out DIR                       the output folder, made if it is missing (default: no files, the
                                  table only).
  -h, --help                      prints this help and exits.

Output: on stdout, each span's (the cable between point bodies) fundamental [Hz], the modes its
cable can lock into and the dominant one; with --out, DIR/strumming.csv (a row per cable segment)
and DIR/strumming_spans.csv (a row per span); the columns:
docs/tools.md#strumming-tow_sim_strumming.
Exit codes: 0 done; 2 bad arguments or configuration; 3 no steady tow found; 4 cannot write DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

double number(const std::string& text, const std::string& option, double low, double high)
{
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= low && v <= high))
    throw std::invalid_argument(option + " '" + text + "': a number in [" + std::to_string(low) + ", " +
                                std::to_string(high) + "]");
  return v;
}

// SPEED:DIRECTION_DEG, the current flowing toward DIRECTION_DEG from the ship's heading (+x), counter-clockwise.
Eigen::Vector3d current(const std::string& text)
{
  const size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw std::invalid_argument("--current '" + text + "' must be SPEED:DIRECTION_DEG");
  const double speed = number(text.substr(0, colon), "--current speed", -20.0, 20.0);
  const double direction = number(text.substr(colon + 1), "--current direction", -360.0, 360.0) * kPi / 180.0;
  return speed * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
}

int write(const std::string& dir, const StrummingAnalysis& a)
{
  std::error_code made;
  std::filesystem::create_directories(dir, made);
  std::ofstream rows(dir + "/strumming.csv"), spans(dir + "/strumming_spans.csv");
  if (!rows || !spans)
  {
    std::fprintf(stderr, "tow_sim_strumming: cannot write into %s\n", dir.c_str());
    return 4;
  }
  rows.precision(10);
  spans.precision(10);
  rows << "segment,section,span,arc_length,depth,normal_speed,shedding_frequency,tension,wave_speed,lowest_mode,"
          "highest_mode,drag_amplification\n";
  for (size_t i = 0; i < a.segments.size(); ++i)
  {
    const StrummingSegment& s = a.segments[i];
    rows << i + 1 << ',' << s.section << ',' << s.span << ',' << s.arc_length << ',' << s.depth << ',' << s.normal_speed
         << ',' << s.shedding_frequency << ',' << s.tension << ',' << s.wave_speed << ',' << s.lowest_mode << ','
         << s.highest_mode << ',' << s.drag_amplification << '\n';
  }
  spans << "span,start,end,travel_time,fundamental,lowest_mode,highest_mode,dominant_mode,dominant_frequency,"
           "power_in_length\n";
  for (size_t k = 0; k < a.spans.size(); ++k)
  {
    const StrummingSpan& s = a.spans[k];
    spans << k << ',' << s.start << ',' << s.end << ',' << s.travel_time << ',' << s.fundamental << ',' << s.lowest_mode
          << ',' << s.highest_mode << ',' << s.dominant_mode << ',' << s.dominant_frequency << ',' << s.power_in_length
          << '\n';
  }
  std::printf("tow_sim_strumming: wrote %s/strumming.csv and strumming_spans.csv\n", dir.c_str());
  return 0;
}

void print(const StrummingAnalysis& a)
{
  double f_low = 0.0, f_high = 0.0;
  for (const StrummingSegment& s : a.segments)
  {
    f_low =
        (f_low == 0.0 || (s.shedding_frequency > 0.0 && s.shedding_frequency < f_low)) ? s.shedding_frequency : f_low;
    f_high = std::max(f_high, s.shedding_frequency);
  }
  std::printf("shedding frequency along the cable: %.4g .. %.4g Hz (lock-in band +-%.0f %%)\n", f_low, f_high,
              100.0 * a.bandwidth);
  std::printf("%4s %10s %10s %14s %16s %14s %14s %14s\n", "span", "from [m]", "to [m]", "f_1 [Hz]", "modes in band",
              "dominant", "f [Hz]", "power-in [m]");
  for (size_t k = 0; k < a.spans.size(); ++k)
  {
    const StrummingSpan& s = a.spans[k];
    const std::string band =
        s.lowest_mode > 0 ? std::to_string(s.lowest_mode) + ".." + std::to_string(s.highest_mode) : std::string("none");
    std::printf("%4zu %10.2f %10.2f %14.6g %16s %14ld %14.6g %14.2f\n", k, s.start, s.end, s.fundamental, band.c_str(),
                s.dominant_mode, s.dominant_frequency, s.power_in_length);
  }
}
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  std::string config_path, out_dir, speed, cable_out, current_text, bandwidth;
  for (int i = 1; i < argc; ++i)
  {
    const bool has_value = i + 1 < argc;
    const std::string arg = argv[i];
    if (arg == "--config" && has_value)
      config_path = argv[++i];
    else if (arg == "--speed" && has_value)
      speed = argv[++i];
    else if (arg == "--cable-out" && has_value)
      cable_out = argv[++i];
    else if (arg == "--current" && has_value)
      current_text = argv[++i];
    else if (arg == "--bandwidth" && has_value)
      bandwidth = argv[++i];
    else if (arg == "--out" && has_value)
      out_dir = argv[++i];
    else
      return usage(tow_sim::cli::badArgument(kUsage, argc, argv, i));
  }
  if (config_path.empty() || speed.empty())
    return usage("--config and --speed are needed");
  StrummingAnalysis analysis;
  try
  {
    const SimulationConfig config = loadConfigFile(config_path);
    const double u = number(speed, "--speed", -20.0, 20.0);
    const double l = cable_out.empty() ? config.cable.length : number(cable_out, "--cable-out", 1e-3, 1e5);
    const Eigen::Vector3d c = current_text.empty() ? Eigen::Vector3d::Zero() : current(current_text);
    const double b = bandwidth.empty() ? 0.2 : number(bandwidth, "--bandwidth", 0.0, 1.0);
    if (b >= 1.0)
      throw std::invalid_argument("--bandwidth '" + bandwidth + "': a number in [0, 1)");
    analysis = steadyTowStrumming(config, u, l, c, b);
  }
  catch (const std::invalid_argument& e)
  {
    return usage(e.what());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_strumming: no steady tow: %s\n", e.what());
    return 3;
  }
  print(analysis);
  return out_dir.empty() ? 0 : write(out_dir, analysis);
}
