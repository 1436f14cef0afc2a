// The batch run of a scenario (tow_sim_batch): a TowRun on the scenario's scripted ship, commands and
// autopilot, sampled every output interval into the rows of timeseries.csv and shapes.csv. The tool only
// parses its arguments and opens the files; tests call this in-process. (Library tow_sim_scenario.)
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
// The columns of timeseries.csv (five more for each of `bodies` point bodies) and of shapes.csv (a `section`
// column with cable sections) (docs/tools.md, "Output files").
std::string timeseriesHeader(size_t bodies = 0);
std::string shapesHeader(bool sections = false);
// The values of timeseries.csv's row for a snapshot, in the header's order; NaN for a blank cell (no seabed,
// no autopilot, a body a parting took off the vehicle side). The Python module's series are these.
std::vector<double> timeseriesValues(const TowSnapshot& s);
// One row of timeseries.csv for a snapshot (no line break), numbers to `precision` significant digits;
// blank cells as documented.
std::string timeseriesRow(const TowSnapshot& s, int precision = 10);
// The rows of shapes.csv for a snapshot: one per joint x_1 .. x_{nu+2}, each ending in a line break.
std::string shapesRows(const TowSnapshot& s, bool sections = false, int precision = 10);

struct BatchResult
{
  double t_reached = 0.0;               // [s] the last output time written
  long rows = 0;                        // timeseries rows written
  std::string start_warning;            // the initial shape's fallback, if it had to fall back
  std::optional<PartingEvent> parting;  // the cable parted (cable.break_at_breaking_load)
};

// events.csv: a header and a row per event (t, event, joint, tension): the cable parting, if it did.
const char* eventsHeader();
std::string eventsRows(const BatchResult& result);

// Runs the scenario, writing the headers and a row per output interval (shapes every shape interval and at
// the end). Throws std::runtime_error when the run diverges; `result` then says how far the rows go.
// `progress` (may be empty) is called with each output time. A scenario starting from a saved state
// (initial_state type file) starts at the state's time, its first row the first output time from then on;
// continuing a state saved at an output time of the same scenario gives the very rows the uninterrupted run
// wrote from that time on. `save_state` (may be empty) gets the run's state at each of save_state_at, taken
// before that time's row (none once the cable has parted: such states are not saved).
// A state saved with the ship elsewhere (another scenario's, the node's) is placed behind this scenario's ship
// at its time (relocate(), said in start_warning). A state that cannot be read or does not fit the run throws
// BadInitialState.
// `precision`: significant digits of the CSV's numbers (tow_sim_batch --precision).
// `observe` (may be empty) gets every snapshot a row is written from (the survey sensors' truth).
using SaveStateSink = std::function<void(double t, const RunState& state)>;
using SnapshotSink = std::function<void(const TowSnapshot& s)>;
struct BadInitialState : std::invalid_argument
{
  using std::invalid_argument::invalid_argument;
};
void runScenario(const Scenario& scenario, std::ostream& series, std::ostream& shapes, BatchResult& result,
                 const std::function<void(double t)>& progress = {}, const SaveStateSink& save_state = {},
                 int precision = 10, const SnapshotSink& observe = {});

// What tow_sim_batch does with a scenario file and an output folder (the tool, the Python module's run_batch and
// tow_sim_sweep's in-process runs): reads the scenario, writes DIR/timeseries.csv, shapes.csv, scenario.yaml,
// events.csv and the state files, and returns the tool's exit code with what it says on stdout (`report`) and
// stderr (`errors`), each line ending in a line break. `progress` (may be empty) gets each output time and the
// scenario's duration [s].
struct BatchOutcome
{
  int code = 0;           // 0 done; 2 bad scenario or saved initial state; 3 the run diverged; 4 cannot write
  std::string report;     // stdout
  std::string errors;     // stderr
  long rows = 0;          // timeseries rows written
  double duration = 0.0;  // [s] the scenario's (0 when it could not be read)
};
BatchOutcome runBatchFile(const std::string& scenario_path, const std::string& out_dir, int precision = 10,
                          const std::function<void(double t, double duration)>& progress = {});

// The scenario's run as runScenario starts it (the Python module's Run too): the scripted ship sampled
// over the scenario's duration, the run with its commands and autopilot, started at t = 0 by the initial
// shape or restored from the scenario's saved state (throws BadInitialState for one that cannot be read
// or does not fit).
struct StartedScenario
{
  std::shared_ptr<ShipHistory> ship;
  std::unique_ptr<TowRun> run;
  long first_output = 0;      // the index of the first output time (after a saved state's time)
  std::string start_warning;  // the initial shape's fallback, or the saved state's relocation
};
StartedScenario startScenario(const Scenario& scenario);

}  // namespace tow_sim
