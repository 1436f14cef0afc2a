// tow_sim_nav: where the towfish was, reprocessed offline from a survey's measurements with the cable model
// (tow_nav.h, docs/survey.md), beside the layback rules survey software uses, without roscore.
//   tow_sim_nav --config FILE.yaml --measurements IN.csv --out DIR
//   tow_sim_nav --config FILE.yaml --bag SURVEY.bag [--topics PREFIX] [--nav-config NODE.yaml] --out DIR
// IN.csv: measurements.csv's columns (survey_measurement.h; tow_sim_batch writes one for a scenario with
// sensors). Writes DIR/estimate.csv (t,x,y,z,sigma_x,sigma_y,sigma_z,layback,cross_track; a row per input row,
// empty cells until the model has started) and DIR/baselines.csv (t,pythagoras_x,pythagoras_y,track_x,track_y,
// catenary_x,catenary_y; empty cells until a ship fix, a cable out and a depth have come). The configuration's
// `nav:` section and `tow_point` set the estimator. A bag (catkin build only) holds the survey/ topics
// tow_nav_node subscribes, under PREFIX (default /); NODE.yaml has tow_nav_node's keys (its origin, heading
// convention, depth source; config/tow_nav.yaml), and the rows' t are seconds after the bag's first stamp
// (whole seconds, printed). Exit codes: 0 done; 2 bad arguments, configuration or
// measurements; 4 cannot write DIR.
#include <yaml-cpp/yaml.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>

#include "cli.h"
#include "tow_sim/config/config.h"
#include "tow_sim/config/nav_params.h"
#include "tow_sim/core/io/measurement_csv.h"
#ifdef TOW_SIM_NAV_BAG
#include "tow_sim/ros/survey_bag.h"
#endif

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_nav";
constexpr char kUsage[] =
    "tow_sim_nav --config FILE.yaml --measurements IN.csv --out DIR\n"
    "       tow_sim_nav --config FILE.yaml --bag SURVEY.bag [--topics PREFIX] [--nav-config NODE.yaml]\n"
    "                   --out DIR";
constexpr char kHelp[] = R"(
Where the towfish was, reprocessed offline from a survey's measurements with the cable model, beside
the layback rules survey software uses, without roscore (docs/survey.md).

Options:
  --config FILE.yaml       the configuration, in the node's YAML format; its nav: section and
                           tow_point [m] set the estimator. Required.
  --measurements IN.csv    the survey's rows, in measurements.csv's columns (tow_sim_batch writes
                           one for a scenario with sensors). This or --bag is required.
  --bag SURVEY.bag         a bag of the survey/ topics tow_nav_node subscribes (the catkin build
                           only); the rows' t are seconds after the bag's first stamp (printed).
  --topics PREFIX          the namespace of the bag's survey/ topics (default /).
  --nav-config NODE.yaml   tow_nav_node's keys for the bag (its origin, heading convention, depth
                           source; config/tow_nav.yaml). Default: tow_nav_node's defaults.
  --out DIR                the output folder, made if it is missing. Required.
  -h, --help               prints this help and exits.

Output: DIR/estimate.csv (t [s]; x, y, z: the towfish's CG in the world frame, ENU [m]; sigma_x,
sigma_y, sigma_z: their standard deviations [m]; layback, cross_track [m]; a row per input row,
empty cells until the model has started) and DIR/baselines.csv (t [s]; pythagoras_x, pythagoras_y,
track_x, track_y, catenary_x, catenary_y [m]: the layback rules' positions; empty cells until a ship
fix, a cable out and a depth have come); a summary on stdout.
Exit codes: 0 done; 2 bad arguments, configuration or measurements; 4 cannot write DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

struct Args
{
  std::string config, measurements, bag, topics = "/", nav_config, out;
};

// The rows from the CSV or the bag; throws std::exception with the reason.
std::vector<SurveyMeasurement> readRows(const Args& a, const SimulationConfig& config, const TowNavParams& params)
{
  if (!a.measurements.empty())
    return readSurveyMeasurements(a.measurements);
#ifdef TOW_SIM_NAV_BAG
  const TowNavNodeParams node =
      a.nav_config.empty() ? TowNavNodeParams() : readTowNavNodeParams(YAML::LoadFile(a.nav_config), a.nav_config);
  const SurveyBag bag = readSurveyBag(a.bag, a.topics, surveyRowSettings(node, params, config));
  std::printf("tow_sim_nav: %s: %ld survey messages, %ld refused%s%s, %ld late; t = 0 at %.0f s (ROS time)\n",
              a.bag.c_str(), bag.messages, bag.refused,
              bag.first_refusal.empty() ? "" : ", the first: ", bag.first_refusal.c_str(), bag.late, bag.epoch.toSec());
  return bag.rows;
#else
  (void)config, (void)params;
  throw std::invalid_argument("--bag needs tow_sim_nav from the catkin build (this one is the core-only build)");
#endif
}

// The cells of a row, numbers to 10 significant digits; an empty cell for NaN.
std::string cells(std::initializer_list<double> values)
{
  std::string row;
  char buffer[64];
  bool first = true;
  for (double v : values)
  {
    if (!first)
      row += ',';
    first = false;
    if (!std::isnan(v))
    {
      std::snprintf(buffer, sizeof buffer, "%.10g", v);
      row += buffer;
    }
  }
  return row;
}

std::string estimateRow(const TowNavEstimate& e)
{
  const double n = std::nan("");
  if (!e.valid)
    return cells({ e.t, n, n, n, n, n, n, n, n });
  return cells({ e.t, e.p_W.x(), e.p_W.y(), e.p_W.z(), std::sqrt(e.covariance(0, 0)), std::sqrt(e.covariance(1, 1)),
                 std::sqrt(e.covariance(2, 2)), e.layback, e.cross_track });
}

std::string baselineRow(double t, const std::optional<LaybackFixes>& f)
{
  const double n = std::nan("");
  if (!f)
    return cells({ t, n, n, n, n, n, n });
  return cells(
      { t, f->pythagoras.x(), f->pythagoras.y(), f->track.x(), f->track.y(), f->catenary.x(), f->catenary.y() });
}

int run(const Args& args)
{
  const std::string& out_dir = args.out;
  SimulationConfig config;
  TowNavParams params;
  std::vector<SurveyMeasurement> rows;
  try
  {
    config = loadConfigFile(args.config);
    params = loadNavParams(YAML::LoadFile(args.config));
    rows = readRows(args, config, params);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_nav: %s\n", e.what());
    return 2;
  }
  std::error_code made;
  std::filesystem::create_directories(out_dir, made);
  std::ofstream estimate(out_dir + "/estimate.csv"), baselines(out_dir + "/baselines.csv");
  if (!estimate || !baselines)
  {
    std::fprintf(stderr, "tow_sim_nav: cannot write into %s\n", out_dir.c_str());
    return 4;
  }
  estimate << "t,x,y,z,sigma_x,sigma_y,sigma_z,layback,cross_track\n";
  baselines << "t,pythagoras_x,pythagoras_y,track_x,track_y,catenary_x,catenary_y\n";
  const auto start = std::chrono::steady_clock::now();
  TowNav nav(config, params);
  TowNavEstimate last;
  for (const SurveyMeasurement& row : rows)
  {
    last = nav.update(row);
    estimate << estimateRow(last) << '\n';
    baselines << baselineRow(row.t, nav.baselines()) << '\n';
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!nav.started())
    std::fprintf(stderr,
                 "tow_sim_nav: warning: the model never started: it needs ship_x, ship_y and ship_heading over "
                 "nav.start_after = %g s; estimate.csv has no positions\n",
                 params.start_after);
  std::printf(
      "tow_sim_nav: %zu rows (%.0f s of survey) in %.1f s; current estimated (%.3f, %.3f) m/s, drag scale "
      "%.3f; rejected %ld rows, %ld ship fixes, %ld USBL fixes, %ld depths; wrote %s/estimate.csv, "
      "baselines.csv\n",
      rows.size(), rows.empty() ? 0.0 : rows.back().t - rows.front().t, wall, last.current.x(), last.current.y(),
      last.drag_scale, last.rows_rejected, last.fixes_rejected, last.usbl_rejected, last.depths_rejected,
      out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  Args a;
  const std::map<std::string, std::string*> options = {
    { "--config", &a.config }, { "--measurements", &a.measurements }, { "--bag", &a.bag },
    { "--topics", &a.topics }, { "--nav-config", &a.nav_config },     { "--out", &a.out }
  };
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto option = options.find(arg);
    if (option == options.end())
      return usage("unknown argument '" + arg + "'");
    if (i + 1 >= argc)
      return usage(arg + " needs a value");
    *option->second = argv[++i];
  }
  if (a.config.empty() || a.out.empty() || a.measurements.empty() == a.bag.empty())
    return usage("--config, --out and one of --measurements and --bag are required");
  try
  {
    return run(a);
  }
  catch (const std::exception& e)  // a run that cannot go on (the configuration's own checks)
  {
    std::fprintf(stderr, "tow_sim_nav: %s\n", e.what());
    return 2;
  }
}
