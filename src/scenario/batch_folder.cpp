// tow_sim_batch's work on a scenario file and an output folder (batch_run.h, runBatchFile): the tool, the Python
// module's run_batch and tow_sim_sweep's in-process runs all go through here, so they write the same files and
// say the same things.
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>
#include <vector>

#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/core/survey/survey_sensors.h"
#include "tow_sim/scenario/batch_run.h"

namespace tow_sim
{
namespace
{
std::string format(const char* fmt, ...)
{
  va_list args;
  va_start(args, fmt);
  va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, fmt, args);
  va_end(args);
  std::string text(static_cast<size_t>(std::max(size, 0)), '\0');
  std::vsnprintf(text.data(), text.size() + 1, fmt, again);
  va_end(again);
  return text;
}

// events.csv, and the parting said in the report.
void writeEvents(const std::string& out_dir, const BatchResult& result, BatchOutcome& outcome)
{
  std::ofstream(out_dir + "/events.csv") << eventsHeader() << '\n' << eventsRows(result);
  if (result.parting)
    outcome.report += format(
        "tow_sim_batch: the cable parted at t = %.3f s at joint %d (1: the tow point) under %.0f N; the vehicle "
        "side goes on with a free end (events.csv)\n",
        result.parting->t, result.parting->joint, result.parting->tension);
}

// The state file's name for time t: %g's six digits, or every digit where those would name two times alike.
std::string stateName(double t)
{
  std::string name = format("state_%g.txt", t);
  if (std::strtod(name.c_str() + 6, nullptr) != t)
    name = format("state_%.17g.txt", t);
  return name;
}

// measurements.csv: the survey sensors' rows as the snapshots come (sensors.enabled).
class MeasurementWriter
{
public:
  MeasurementWriter(const SurveySensorParams& params, std::ostream& out, int precision)
      : sensors_(params), out_(out), precision_(precision)
  {
    out_ << surveyMeasurementHeader() << '\n';
  }
  void observe(const TowSnapshot& s)
  {
    sensors_.observe(s);
    for (const SurveyMeasurement& row : sensors_.take(s.t))
      out_ << surveyMeasurementRow(row, precision_) << '\n';
  }

private:
  SurveySensors sensors_;
  std::ostream& out_;
  int precision_;
};

// Runs the scenario into the open CSV files and the state files.
void runInto(const Scenario& sc, const std::string& out_dir, std::ostream& series, std::ostream& shapes, int precision,
             const std::function<void(double t)>& progress, const SnapshotSink& observe, BatchOutcome& outcome)
{
  BatchResult result;
  std::string saved;
  bool unwritten = false;
  auto save = [&](double t, const RunState& state)
  {
    const std::string name = stateName(t);
    try
    {
      writeRunState(out_dir + "/" + name, state);
      saved += ", " + name;
    }
    catch (const std::exception& e)
    {
      outcome.errors += std::string("tow_sim_batch: ") + e.what() + "\n";
      unwritten = true;
    }
  };
  try
  {
    runScenario(sc, series, shapes, result, progress, save, precision, observe);
  }
  catch (const BadInitialState& e)
  {
    outcome.errors += std::string("tow_sim_batch: bad initial state: ") + e.what() + "\n";
    outcome.code = 2;
    return;
  }
  catch (const std::exception& e)
  {
    writeEvents(out_dir, result, outcome);
    if (!result.start_warning.empty())  // the fallback start is the likeliest cause: say so first
      outcome.errors += "tow_sim_batch: " + result.start_warning + "\n";
    outcome.errors += format(
        "tow_sim_batch: the run stopped: %s\ntow_sim_batch: the CSV files in %s are INCOMPLETE: they hold the run "
        "up to t = %.3f s of %.3f s\n",
        e.what(), out_dir.c_str(), result.t_reached, sc.duration);
    outcome.rows = result.rows;
    outcome.code = 3;
    return;
  }
  writeEvents(out_dir, result, outcome);
  if (!result.start_warning.empty())
    outcome.errors += "tow_sim_batch: " + result.start_warning + "\n";
  outcome.report += format(
      "tow_sim_batch: %.0f s simulated; wrote %s/timeseries.csv (%ld rows), shapes.csv, "
      "scenario.yaml, events.csv%s%s\n",
      sc.duration, out_dir.c_str(), result.rows, sc.sensors.enabled ? ", measurements.csv" : "", saved.c_str());
  outcome.rows = result.rows;
  outcome.code = unwritten ? 4 : 0;
}
}  // namespace

BatchOutcome runBatchFile(const std::string& scenario_path, const std::string& out_dir, int precision,
                          const std::function<void(double t, double duration)>& progress)
{
  BatchOutcome outcome;
  Scenario sc;
  try
  {
    sc = loadScenarioFile(scenario_path);
  }
  catch (const std::exception& e)
  {
    outcome.errors = "tow_sim_batch: bad scenario " + scenario_path + ": " + e.what() + "\n";
    outcome.code = 2;
    return outcome;
  }
  std::error_code made;  // with its parents (out/run); a failure shows as the files not opening
  std::filesystem::create_directories(out_dir, made);
  std::ofstream series(out_dir + "/timeseries.csv"), shapes(out_dir + "/shapes.csv"),
      resolved(out_dir + "/scenario.yaml");
  if (!series || !shapes || !resolved)
  {
    outcome.errors = "tow_sim_batch: cannot write into " + out_dir + "\n";
    outcome.code = 4;
    return outcome;
  }
  resolved << "# " << scenario_path << " with every default filled in, as run by tow_sim_batch\n" << toYaml(sc) << "\n";
  resolved.close();
  outcome.duration = sc.duration;
  std::function<void(double)> each;
  if (progress)
    each = [&progress, &sc](double t) { progress(t, sc.duration); };
  std::ofstream measurements;
  std::unique_ptr<MeasurementWriter> writer;
  SnapshotSink observe;
  if (sc.sensors.enabled)
  {
    measurements.open(out_dir + "/measurements.csv");
    if (!measurements)
    {
      outcome.errors = "tow_sim_batch: cannot write into " + out_dir + "\n";
      outcome.code = 4;
      return outcome;
    }
    writer = std::make_unique<MeasurementWriter>(sc.sensors, measurements, precision);
    observe = [&writer](const TowSnapshot& s) { writer->observe(s); };
  }
  runInto(sc, out_dir, series, shapes, precision, each, observe, outcome);
  return outcome;
}

}  // namespace tow_sim
