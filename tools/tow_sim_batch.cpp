// tow_sim_batch: runs a scenario faster than real time, without roscore.
//   tow_sim_batch --scenario FILE.yaml --out DIR [--precision DIGITS]
// Writes DIR/timeseries.csv, DIR/shapes.csv, DIR/scenario.yaml (the scenario with every default
// filled in), DIR/events.csv (the cable parting, if it did) and DIR/state_<t>.txt at each
// simulation.save_state_at. Exit codes: 0 done; 2 bad arguments,
// scenario or saved initial state; 3 the run diverged (the CSV files then hold the run up to the last good
// output and the error says so); 4 cannot write DIR. --precision: significant digits of the CSV's numbers
// (6..17, default 10; 17 gives every double exactly).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/scenario/batch_run.h"

namespace
{
using namespace tow_sim;

int usage(const std::string& why)
{
  std::fprintf(stderr, "tow_sim_batch: %s\nusage: tow_sim_batch --scenario FILE.yaml --out DIR [--precision DIGITS]\n",
               why.c_str());
  return 2;
}

// A progress bar on stderr for runs longer than 2 s of wall time.
class Progress
{
public:
  explicit Progress(double total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  void update(double done)
  {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int percent = static_cast<int>(100.0 * done / total_);
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
  double total_;
  std::chrono::steady_clock::time_point start_;
  int next_ = 0;
  bool shown_ = false;
};
// events.csv, and the parting said on stdout.
void writeEvents(const std::string& out_dir, const BatchResult& result)
{
  std::ofstream(out_dir + "/events.csv") << eventsHeader() << '\n' << eventsRows(result);
  if (result.parting)
    std::printf(
        "tow_sim_batch: the cable parted at t = %.3f s at joint %d (1: the tow point) under %.0f N; the "
        "vehicle side goes on with a free end (events.csv)\n",
        result.parting->t, result.parting->joint, result.parting->tension);
}

// Runs the scenario into the open CSV files and the state files, and says how it went (the exit code).
int runAndReport(const Scenario& sc, const std::string& out_dir, std::ostream& series, std::ostream& shapes,
                 int precision)
{
  Progress progress(sc.duration);
  BatchResult result;
  std::vector<std::string> saved;
  bool unwritten = false;
  auto save = [&out_dir, &saved, &unwritten](double t, const RunState& state)
  {
    char name[64];
    std::snprintf(name, sizeof name, "/state_%g.txt", t);
    if (std::strtod(name + 7, nullptr) != t)  // %g's six digits would name two times alike
      std::snprintf(name, sizeof name, "/state_%.17g.txt", t);
    try
    {
      writeRunState(out_dir + name, state);
      saved.push_back(name + 1);
    }
    catch (const std::exception& e)
    {
      std::fprintf(stderr, "tow_sim_batch: %s\n", e.what());
      unwritten = true;
    }
  };
  try
  {
    runScenario(
        sc, series, shapes, result, [&progress](double t) { progress.update(t); }, save, precision);
  }
  catch (const BadInitialState& e)
  {
    progress.finish();
    std::fprintf(stderr, "tow_sim_batch: bad initial state: %s\n", e.what());
    return 2;
  }
  catch (const std::exception& e)
  {
    progress.finish();
    writeEvents(out_dir, result);
    if (!result.start_warning.empty())  // the fallback start is the likeliest cause: say so first
      std::fprintf(stderr, "tow_sim_batch: %s\n", result.start_warning.c_str());
    std::fprintf(stderr,
                 "tow_sim_batch: the run stopped: %s\ntow_sim_batch: the CSV files in %s are INCOMPLETE: they hold "
                 "the run up to t = %.3f s of %.3f s\n",
                 e.what(), out_dir.c_str(), result.t_reached, sc.duration);
    return 3;
  }
  progress.finish();
  writeEvents(out_dir, result);
  if (!result.start_warning.empty())
    std::fprintf(stderr, "tow_sim_batch: %s\n", result.start_warning.c_str());
  std::string states;
  for (const std::string& name : saved)
    states += ", " + name;
  std::printf(
      "tow_sim_batch: %.0f s simulated; wrote %s/timeseries.csv (%ld rows), shapes.csv, scenario.yaml, "
      "events.csv%s\n",
      sc.duration, out_dir.c_str(), result.rows, states.c_str());
  return unwritten ? 4 : 0;
}
}  // namespace

int main(int argc, char** argv)
{
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
      return usage(std::string("unknown argument '") + argv[i] + "'");
  }
  if (scenario_path.empty() || out_dir.empty())
    return usage("both --scenario and --out are needed");
  Scenario sc;
  try
  {
    sc = loadScenarioFile(scenario_path);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_batch: bad scenario %s: %s\n", scenario_path.c_str(), e.what());
    return 2;
  }
  std::error_code made;  // with its parents (out/run); a failure shows as the files not opening
  std::filesystem::create_directories(out_dir, made);
  std::ofstream series(out_dir + "/timeseries.csv"), shapes(out_dir + "/shapes.csv"),
      resolved(out_dir + "/scenario.yaml");
  if (!series || !shapes || !resolved)
  {
    std::fprintf(stderr, "tow_sim_batch: cannot write into %s\n", out_dir.c_str());
    return 4;
  }
  resolved << "# " << scenario_path << " with every default filled in, as run by tow_sim_batch\n" << toYaml(sc) << "\n";
  resolved.close();

  return runAndReport(sc, out_dir, series, shapes, precision);
}
