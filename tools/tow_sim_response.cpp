// tow_sim_response: the steady tow's response to the ship's motion in the frequency domain, without roscore.
//   tow_sim_response --config FILE.yaml --speed U [--cable-out L] --input heave|surge|sway|pitch
//                    --periods FROM:TO:STEP [--tow-point X,Y,Z] --out DIR
//   tow_sim_response --scenario FILE.yaml [--cable-out L] --out DIR
// Writes DIR/response.csv: per period [s], the amplitude per metre (per radian for pitch) of input and the phase
// [deg] relative to the input's displacement of the vehicle's heave, surge, sway [m], pitch [rad] and of the
// tension at the ship and at the vehicle [N] (docs/tools.md, "Response to ship motion"). The tow point [m] is in
// the ship frame (FLU) from the ship's reference point (default -20,0,0): the ship's pitch (REP-103, bow down
// positive) moves it by pitch x its position. The second form takes a scenario's sea, ship (speed, heading, RAOs,
// tow point) and configuration and writes DIR/sea_state.csv: per wave component, the amplitudes [m, rad, N] of
// the tow point's heave and the outputs above, and prints their standard deviations and significant amplitudes
// (docs/tools.md, "In a sea state"). Exit codes: 0 done; 2 bad arguments, configuration or
// scenario; 3 no steady tow found; 4 cannot write DIR.
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/scenario/sea_state.h"
#include "tow_sim/scenario/towing_chart.h"

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_response";
constexpr char kUsage[] =
    "tow_sim_response --config FILE.yaml --speed U [--cable-out L] --input heave|surge|sway|pitch\n"
    "                        --periods FROM:TO:STEP [--tow-point X,Y,Z] --out DIR\n"
    "       tow_sim_response --scenario FILE.yaml [--cable-out L] --out DIR";
constexpr char kHelp[] = R"(
The steady tow's response to the ship's motion in the frequency domain, without roscore: to the tow
point's heave, surge or sway or the ship's pitch over a range of periods (first form), or to a
scenario's sea state through the ship's RAOs (second form). Linear, about the steady tow.

Options of the first form (--config, --speed, --input and --periods are required):
  --config FILE.yaml       the configuration, in the node's YAML format (config/tow_sim.yaml).
  --speed U                the ship's speed [m/s].
  --input MOTION           the ship's motion: heave, surge or sway (the tow point moving 1 m) or
                           pitch (the ship pitching 1 rad, bow down positive, about its reference
                           point).
  --periods FROM:TO:STEP   the periods [s], each in (0, 1e5]; one value is a single period.
  --tow-point X,Y,Z        the tow point [m] in the ship frame (FLU) from the ship's reference point
                           (default -20,0,0); it sets how pitch moves the tow point.
Options of the second form:
  --scenario FILE.yaml     the scenario whose sea, ship (speed, heading, RAOs, tow point) and
                           configuration to take. Required; only --cable-out and --out go with it.
Options of both forms:
  --cable-out L            the length of cable out [m] (default the configuration's or the
                           scenario's cable.length).
  --out DIR                the output folder, made if it is missing. Required.
  -h, --help               prints this help and exits.

Output: DIR/response.csv (period [s]; for vehicle_heave, vehicle_surge, vehicle_sway [m],
vehicle_pitch [rad], tension_ship and tension_vehicle [N], the amplitude per metre of input (per
radian for pitch) and the phase [deg] relative to the input's displacement). The second form writes
DIR/sea_state.csv (per wave component, the amplitudes [m, rad, N] of the tow point's heave and the
outputs above) and prints their standard deviations and significant amplitudes on stdout. The
columns: docs/tools.md#response-to-ship-motion-tow_sim_response.
Exit codes: 0 done; 2 bad arguments, configuration or scenario; 3 no steady tow found; 4 cannot
write DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

Eigen::Vector3d towPoint(const std::string& text)
{
  std::vector<double> v;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    v.push_back(parseSingle(item, "--tow-point"));
  if (v.size() != 3)
    throw std::invalid_argument("--tow-point " + text + ": X,Y,Z [m] in the ship frame");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

int write(const std::string& dir, const std::vector<MotionResponse>& rows)
{
  std::error_code made;
  std::filesystem::create_directories(dir, made);
  std::ofstream out(dir + "/response.csv");
  if (!out)
  {
    std::fprintf(stderr, "tow_sim_response: cannot write into %s\n", dir.c_str());
    return 4;
  }
  out.precision(10);
  out << "period";
  for (const char* name :
       { "vehicle_heave", "vehicle_surge", "vehicle_sway", "vehicle_pitch", "tension_ship", "tension_vehicle" })
    out << ',' << name << ',' << name << "_phase";
  out << '\n';
  for (const MotionResponse& r : rows)
  {
    out << r.period;
    for (const std::complex<double>& h : { r.heave, r.surge, r.sway, r.pitch, r.tension_ship, r.tension_vehicle })
      out << ',' << std::abs(h) << ',' << std::arg(h) * 180.0 / kPi;
    out << '\n';
  }
  std::printf("tow_sim_response: wrote %s/response.csv (%zu periods)\n", dir.c_str(), rows.size());
  return 0;
}

int writeSeaState(const std::string& dir, const SeaStateResponse& r)
{
  std::error_code made;
  std::filesystem::create_directories(dir, made);
  std::ofstream out(dir + "/sea_state.csv");
  if (!out)
  {
    std::fprintf(stderr, "tow_sim_response: cannot write into %s\n", dir.c_str());
    return 4;
  }
  out.precision(10);
  out << "frequency,encounter_frequency,direction,amplitude";
  for (const char* name : SeaStateResponse::names)
    out << ',' << name << ',' << name << "_phase";
  out << '\n';
  for (const SeaStateComponent& c : r.components)
  {
    out << c.frequency << ',' << c.encounter_frequency << ',' << c.direction * 180.0 / kPi << ',' << c.amplitude;
    for (const std::complex<double>& h : c.outputs)
      out << ',' << c.amplitude * std::abs(h) << ',' << std::arg(h) * 180.0 / kPi;
    out << '\n';
  }
  std::printf("%-16s %16s %22s\n", "output", "std deviation", "significant amplitude");
  for (int j = 0; j < kSeaStateOutputs; ++j)
    std::printf("%-16s %16.6g %22.6g\n", SeaStateResponse::names[j], r.standard_deviation[j],
                2.0 * r.standard_deviation[j]);
  std::printf("tow_sim_response: wrote %s/sea_state.csv (%zu wave components, ship at %.3g m/s)\n", dir.c_str(),
              r.components.size(), r.speed);
  return 0;
}

int seaState(const std::string& scenario_path, const std::string& cable_out, const std::string& out_dir)
{
  SeaStateResponse r;
  try
  {
    const Scenario scenario = loadScenarioFile(scenario_path);
    std::optional<double> l;
    if (!cable_out.empty())
      l = parseSingle(cable_out, "--cable-out");
    r = seaStateResponse(scenario, l);
  }
  catch (const std::invalid_argument& e)
  {
    return usage(e.what());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_response: no steady tow: %s\n", e.what());
    return 3;
  }
  return writeSeaState(out_dir, r);
}
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  std::string config_path, scenario, speed, cable_out, input, periods, tow_point, out_dir;
  for (int i = 1; i < argc; ++i)
  {
    const bool has_value = i + 1 < argc;
    std::string* target = nullptr;
    for (auto [flag, field] : { std::pair<const char*, std::string*>{ "--config", &config_path },
                                { "--scenario", &scenario },
                                { "--speed", &speed },
                                { "--cable-out", &cable_out },
                                { "--input", &input },
                                { "--periods", &periods },
                                { "--tow-point", &tow_point },
                                { "--out", &out_dir } })
      if (!std::strcmp(argv[i], flag) && has_value)
        target = field;
    if (!target)
      return usage(tow_sim::cli::badArgument(kUsage, argc, argv, i));
    *target = argv[++i];
  }
  if (!scenario.empty())
  {
    if (!(config_path.empty() && speed.empty() && input.empty() && periods.empty() && tow_point.empty()))
      return usage("--scenario takes only --cable-out and --out");
    return out_dir.empty() ? usage("--scenario needs --out") : seaState(scenario, cable_out, out_dir);
  }
  if (config_path.empty() || speed.empty() || input.empty() || periods.empty() || out_dir.empty())
    return usage("--config, --speed, --input, --periods and --out are needed");
  std::vector<MotionResponse> rows;
  try
  {
    const SimulationConfig config = loadConfigFile(config_path);
    const double u = parseSingle(speed, "--speed");
    const double l = cable_out.empty() ? config.cable.length : parseSingle(cable_out, "--cable-out");
    const Eigen::Vector3d motion = towPointMotion(input, towPoint(tow_point.empty() ? "-20,0,0" : tow_point));
    rows = steadyTowResponse(config, u, l, Eigen::Vector3d::Zero(), motion, parseRange(periods, "--periods"));
  }
  catch (const std::invalid_argument& e)
  {
    return usage(e.what());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_response: no steady tow: %s\n", e.what());
    return 3;
  }
  return write(out_dir, rows);
}
