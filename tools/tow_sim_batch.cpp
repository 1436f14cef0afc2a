// tow_sim_batch: runs a scenario faster than real time, without roscore.
//   tow_sim_batch --scenario FILE.yaml --out DIR [--precision DIGITS]
// Writes DIR/timeseries.csv, DIR/shapes.csv, DIR/scenario.yaml (the scenario with every default
// filled in), DIR/events.csv (the cable parting, if it did) and DIR/state_<t>.txt at each
// simulation.save_state_at. Exit codes: 0 done; 2 bad arguments,
// scenario or saved initial state; 3 the run diverged (the CSV files then hold the run up to the last good
// output and the error says so); 4 cannot write DIR. --precision: significant digits of the CSV's numbers
// (6..17, default 10; 17 gives every double exactly). The work is runBatchFile (batch_run.h), which the Python
// module's run_batch and tow_sim_sweep's in-process runs share.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cli.h"
#include "tow_sim/scenario/batch_run.h"

namespace
{
using namespace tow_sim;

constexpr char kTool[] = "tow_sim_batch";
constexpr char kUsage[] = "tow_sim_batch --scenario FILE.yaml --out DIR [--precision DIGITS]";
constexpr char kHelp[] = R"(
Runs a scenario (the ship's manoeuvres, fin, thrust and winch commands, autopilot, sea) faster than
real time, without roscore.

Options:
  --scenario FILE.yaml  the scenario to run (docs/tools.md#scenario-files; every key with its unit,
                        default and range: docs/parameters.md). Required.
  --out DIR             the output folder, made if it is missing. Required.
  --precision DIGITS    significant digits of the CSV files' numbers, a whole number in [6, 17]
                        (default 10; 17 writes every double exactly).
  -h, --help            prints this help and exits.

Output: DIR/timeseries.csv, DIR/shapes.csv, DIR/scenario.yaml (the scenario with every default
filled in), DIR/events.csv (the cable parting, if it did), DIR/measurements.csv (with
sensors.enabled) and DIR/state_<t>.txt at each simulation.save_state_at [s]; a summary on stdout, a
progress bar on stderr for runs longer than 2 s of wall time.
Exit codes: 0 done; 2 bad arguments, scenario or saved initial state; 3 the run diverged (the CSV
files then hold the run up to the last good output); 4 cannot write DIR.
)";

int usage(const std::string& why)
{
  return cli::fail(kTool, kUsage, why);
}

// A progress bar on stderr for runs longer than 2 s of wall time.
class Progress
{
public:
  Progress() : start_(std::chrono::steady_clock::now()) {}
  void update(double done, double total)
  {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int percent = static_cast<int>(100.0 * done / total);
    if (wall < 2.0 || percent < next_)
      return;
    next_ = percent + 5;
    std::fprintf(stderr, "\r[%-20s] %3d%%  t = %.0f s  (%.0fx real time)", std::string(percent / 5, '#').c_str(),
                 percent, done, done / wall);
    shown_ = true;
  }
  void finish()
  {
    if (shown_)
      std::fprintf(stderr, "\n");
  }

private:
  std::chrono::steady_clock::time_point start_;
  int next_ = 0;
  bool shown_ = false;
};
}  // namespace

int main(int argc, char** argv)
{
  if (cli::wantsHelp(argc, argv))
    return cli::printHelp(kUsage, kHelp);
  std::string scenario_path, out_dir;
  int precision = 10;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--scenario") && i + 1 < argc)
      scenario_path = argv[++i];
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
      out_dir = argv[++i];
    else if (!std::strcmp(argv[i], "--precision") && i + 1 < argc)
    {
      char* end = nullptr;
      const long digits = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || digits < 6 || digits > 17)
        return usage(std::string("--precision ") + argv[i] + ": a whole number of digits in [6, 17]");
      precision = static_cast<int>(digits);
    }
    else
      return usage(tow_sim::cli::badArgument(kUsage, argc, argv, i));
  }
  if (scenario_path.empty() || out_dir.empty())
    return usage("both --scenario and --out are needed");
  Progress progress;
  const BatchOutcome outcome = runBatchFile(scenario_path, out_dir, precision,
                                            [&progress](double t, double duration) { progress.update(t, duration); });
  progress.finish();
  std::fputs(outcome.report.c_str(), stdout);
  std::fputs(outcome.errors.c_str(), stderr);
  return outcome.code;
}
