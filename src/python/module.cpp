// tow_sim._core: the ROS-free core from Python (docs/python.md). The package tow_sim (python/tow_sim) imports it.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <complex>
#include <sstream>
#include <stdexcept>

#include "convert.h"
#include "python_run.h"
#include "tow_sim/config/config.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/sea_state.h"
#include "tow_sim/scenario/towing_chart.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace tow_sim::python
{
namespace
{
std::string yamlText(const YAML::Node& node)
{
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << node;
  return out.c_str();
}

// As a configuration file with this content: loadConfigFile's checks, top-level keys included.
SimulationConfig configFrom(const YAML::Node& root, const std::string& base_dir)
{
  SimulationConfig config = loadConfig(root, "", base_dir);
  requireKnownKeys(root, "", configurationFileKeys());
  return config;
}

void bindConfig(py::module_& m)
{
  py::class_<SimulationConfig>(m, "Config", "A validated configuration (config/tow_sim.yaml's keys).")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::string& base_dir) { return configFrom(toYamlNode(d, ""), base_dir); }, "d"_a,
          "base_dir"_a = "",
          "The configuration a YAML file with this content would give (same checks, same messages); relative file "
          "names from base_dir.")
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& base_dir)
          {
            YAML::Node root;
            try
            {
              root = YAML::Load(text);
            }
            catch (const YAML::Exception& e)
            {
              throw std::invalid_argument(std::string("cannot read the YAML text: ") + e.what());
            }
            return configFrom(root, base_dir);
          },
          "text"_a, "base_dir"_a = "", "As from_dict, from YAML text.")
      .def(
          "to_yaml", [](const SimulationConfig& c) { return yamlText(toYaml(c)); },
          "Every key, defaults filled in, as YAML text.")
      .def("keys", &configurationKeys, "Every key and its value as text, flattened: {'cable.length': '500', ...}.")
      .def_property_readonly(
          "cable_length", [](const SimulationConfig& c) { return c.cable.length; }, "[m]")
      .def_property_readonly("segments", [](const SimulationConfig& c) { return c.cable.segments; })
      .def("__repr__", [](const SimulationConfig& c)
           { return "<tow_sim.Config: " + std::to_string(c.cable.length) + " m of cable>"; });
  m.def("load_config", &loadConfigFile, "path"_a, "A configuration file (ValueError naming the key on a bad one).");
}

void bindScenario(py::module_& m)
{
  py::class_<Scenario>(m, "Scenario", "A batch scenario: a configuration, a scripted ship, commands and timing.")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::string& base_dir) { return loadScenario(toYamlNode(d, ""), base_dir); },
          "d"_a, "base_dir"_a = "", "The scenario a YAML file with this content would give.")
      .def("to_yaml", [](const Scenario& s) { return yamlText(toYaml(s)); })
      .def_readonly("config", &Scenario::config)
      .def_readonly("duration", &Scenario::duration, "[s]")
      .def_readonly("output_interval", &Scenario::output_interval, "[s]");
  m.def("load_scenario", &loadScenarioFile, "path"_a, "A scenario file (as tow_sim_batch --scenario reads it).");
  m.def(
      "run_batch",
      [](const std::string& scenario_path, const std::string& out_dir, int precision)
      {
        if (precision < 6 || precision > 17)
          throw std::invalid_argument("precision = " + std::to_string(precision) + ": digits in [6, 17]");
        BatchOutcome outcome;
        {
          py::gil_scoped_release released;
          outcome = runBatchFile(scenario_path, out_dir, precision);
        }
        return py::dict("code"_a = outcome.code, "report"_a = outcome.report, "errors"_a = outcome.errors,
                        "rows"_a = outcome.rows);
      },
      "scenario_path"_a, "out_dir"_a, "precision"_a = 10,
      "What tow_sim_batch --scenario PATH --out DIR does, in process: the same files, and {code (its exit code), "
      "report (its stdout), errors (its stderr), rows}. A bad scenario is code 2, not an exception.");
}

void bindSteadyTow(py::module_& m)
{
  m.def(
      "steady_tow",
      [](const SimulationConfig& c, double speed, std::optional<double> cable_out, const py::object& current)
      {
        const Eigen::Vector3d current_W = vector3(current, "current");
        py::gil_scoped_release released;
        return steadyTow(c, speed, cable_out.value_or(c.cable.length), current_W);
      },
      "config"_a, "speed"_a, "cable_out"_a = py::none(), "current"_a = py::make_tuple(0.0, 0.0, 0.0),
      "The steady tow at speed [m/s] along +x with cable_out [m] (default: the configuration's) in a uniform current "
      "[m/s], as tow_sim_chart and a run's start compute it: a Snapshot at t = 0. RuntimeError when none is found.");
}

void bindChart(py::module_& m)
{
  m.def(
      "towing_chart",
      [](const SimulationConfig& c, const std::vector<double>& speeds, const std::vector<double>& cable_outs,
         const py::object& current)
      {
        const Eigen::Vector3d current_W = vector3(current, "current");
        std::vector<ChartPoint> points;
        {
          py::gil_scoped_release released;
          points = towingChart(c, speeds, cable_outs, current_W);
        }
        std::vector<std::vector<double>> rows;
        py::list errors;
        for (const ChartPoint& p : points)
        {
          rows.push_back({ p.speed, p.cable_out, p.current, p.depth, p.layback, p.tension_ship, p.tension_vehicle,
                           p.ship_angle, p.max_tension, p.converged ? 1.0 : 0.0 });
          errors.append(p.error);
        }
        py::dict chart = seriesDict(chartHeader(), rows);
        chart["converged"] = py::object(chart["converged"]).attr("astype")("bool");
        chart["error"] = errors;
        return chart;
      },
      "config"_a, "speeds"_a, "cable_outs"_a, "current"_a = py::make_tuple(0.0, 0.0, 0.0),
      "chart.csv's columns as arrays (speed varying fastest), NaN where no equilibrium was found and 'error' says "
      "why.");
}

void bindPlan(py::module_& m)
{
  m.def(
      "plan_cable_out",
      [](const SimulationConfig& c, double speed, double target_depth, const py::object& current,
         std::optional<double> min_length, std::optional<double> max_length)
      {
        const Eigen::Vector3d current_W = vector3(current, "current");
        CableOutPlan plan;
        {
          py::gil_scoped_release released;
          plan = planCableOut(c, target_depth, speed, current_W, min_length.value_or(c.winch.min_length),
                              max_length.value_or(c.winch.max_length));
        }
        return py::dict("reachable"_a = plan.reachable, "cable_out"_a = plan.cable_out, "depth"_a = plan.point.depth,
                        "layback"_a = plan.point.layback, "tension_ship"_a = plan.point.tension_ship,
                        "reason"_a = plan.reason);
      },
      "config"_a, "speed"_a, "target_depth"_a, "current"_a = py::make_tuple(0.0, 0.0, 0.0), "min_length"_a = py::none(),
      "max_length"_a = py::none(),
      "The cable out [m] that puts the vehicle at target_depth [m] at speed [m/s] (tow_sim_chart --target-depth), "
      "between the winch's limits unless given.");
}
void bindResponse(py::module_& m)
{
  m.def(
      "response",
      [](const SimulationConfig& c, double speed, const std::string& input, const std::vector<double>& periods,
         std::optional<double> cable_out, const py::object& tow_point)
      {
        const Eigen::Vector3d motion = towPointMotion(input, vector3(tow_point, "tow_point"));
        std::vector<MotionResponse> rows;
        {
          py::gil_scoped_release released;
          rows =
              steadyTowResponse(c, speed, cable_out.value_or(c.cable.length), Eigen::Vector3d::Zero(), motion, periods);
        }
        py::dict out;
        auto column = [&](const char* name, std::complex<double> MotionResponse::*field)
        {
          std::vector<std::complex<double>> values;
          for (const MotionResponse& r : rows)
            values.push_back(r.*field);
          out[name] = py::array(py::cast(values));
        };
        std::vector<double> period;
        for (const MotionResponse& r : rows)
          period.push_back(r.period);
        out["period"] = py::array(py::cast(period));
        column("vehicle_heave", &MotionResponse::heave);
        column("vehicle_surge", &MotionResponse::surge);
        column("vehicle_sway", &MotionResponse::sway);
        column("vehicle_pitch", &MotionResponse::pitch);
        column("tension_ship", &MotionResponse::tension_ship);
        column("tension_vehicle", &MotionResponse::tension_vehicle);
        return out;
      },
      "config"_a, "speed"_a, "input"_a, "periods"_a, "cable_out"_a = py::none(),
      "tow_point"_a = py::make_tuple(-20.0, 0.0, 0.0),
      "The steady tow's response to the ship's heave, surge, sway (per m) or pitch (per rad) at each period [s] "
      "(tow_sim_response): complex amplitudes of the vehicle's heave, surge, sway [m], pitch [rad] and the tensions "
      "[N], phases relative to the input's displacement.");
}

void bindModes(py::module_& m)
{
  m.def(
      "modes",
      [](const SimulationConfig& c, double speed, std::optional<double> cable_out, const py::object& current,
         std::optional<std::size_t> count)
      {
        const Eigen::Vector3d current_W = vector3(current, "current");
        if (count && *count == 0)
          throw py::value_error("count must be at least 1 (or None: every mode)");
        std::vector<Mode> modes;
        {
          py::gil_scoped_release released;
          modes = steadyTowModes(c, speed, cable_out.value_or(c.cable.length), current_W, count.value_or(0));
        }
        py::list out;
        for (const Mode& mode : modes)
          out.append(py::dict("period"_a = mode.period, "frequency"_a = mode.frequency,
                              "damping_ratio"_a = mode.damping_ratio, "dominant"_a = mode.dominant,
                              "shape"_a = Eigen::MatrixX3d(mode.shape.transpose())));
        return out;
      },
      "config"_a, "speed"_a, "cable_out"_a = py::none(), "current"_a = py::make_tuple(0.0, 0.0, 0.0),
      "count"_a = py::none(),
      "The natural modes about the steady tow (tow_sim_modes), in ascending natural frequency: dicts of period [s] "
      "(inf: decays without oscillating), frequency [rad/s], damping_ratio, dominant and shape ((nu + 1, 3) [m]). "
      "count: the lowest count only (O(nu) per iteration; None: every mode, a dense eigenproblem).");
}

void bindStrumming(py::module_& m)
{
  m.def(
      "strumming",
      [](const SimulationConfig& c, double speed, std::optional<double> cable_out, const py::object& current,
         double bandwidth)
      {
        const Eigen::Vector3d current_W = vector3(current, "current");
        StrummingAnalysis a;
        {
          py::gil_scoped_release released;
          a = steadyTowStrumming(c, speed, cable_out.value_or(c.cable.length), current_W, bandwidth);
        }
        py::dict segments, spans;
        auto column = [](py::dict& out, const char* name, const auto& rows, auto field)
        {
          std::vector<std::decay_t<decltype(rows.front().*field)>> values;
          for (const auto& r : rows)
            values.push_back(r.*field);
          out[name] = py::array(py::cast(values));
        };
        column(segments, "section", a.segments, &StrummingSegment::section);
        column(segments, "span", a.segments, &StrummingSegment::span);
        column(segments, "arc_length", a.segments, &StrummingSegment::arc_length);
        column(segments, "depth", a.segments, &StrummingSegment::depth);
        column(segments, "normal_speed", a.segments, &StrummingSegment::normal_speed);
        column(segments, "shedding_frequency", a.segments, &StrummingSegment::shedding_frequency);
        column(segments, "tension", a.segments, &StrummingSegment::tension);
        column(segments, "wave_speed", a.segments, &StrummingSegment::wave_speed);
        column(segments, "lowest_mode", a.segments, &StrummingSegment::lowest_mode);
        column(segments, "highest_mode", a.segments, &StrummingSegment::highest_mode);
        column(segments, "drag_amplification", a.segments, &StrummingSegment::drag_amplification);
        column(spans, "start", a.spans, &StrummingSpan::start);
        column(spans, "end", a.spans, &StrummingSpan::end);
        column(spans, "travel_time", a.spans, &StrummingSpan::travel_time);
        column(spans, "fundamental", a.spans, &StrummingSpan::fundamental);
        column(spans, "lowest_mode", a.spans, &StrummingSpan::lowest_mode);
        column(spans, "highest_mode", a.spans, &StrummingSpan::highest_mode);
        column(spans, "dominant_mode", a.spans, &StrummingSpan::dominant_mode);
        column(spans, "dominant_frequency", a.spans, &StrummingSpan::dominant_frequency);
        column(spans, "power_in_length", a.spans, &StrummingSpan::power_in_length);
        return py::dict("segments"_a = segments, "spans"_a = spans, "bandwidth"_a = a.bandwidth);
      },
      "config"_a, "speed"_a, "cable_out"_a = py::none(), "current"_a = py::make_tuple(0.0, 0.0, 0.0),
      "bandwidth"_a = 0.2,
      "Where the steady tow's cable sheds vortices and which string modes it can lock into (tow_sim_strumming): "
      "{'segments': strumming.csv's columns but segment, 'spans': strumming_spans.csv's, 'bandwidth': b}; frequencies "
      "[Hz].");
}

void bindSeaState(py::module_& m)
{
  m.def(
      "sea_state",
      [](const Scenario& scenario, std::optional<double> cable_out)
      {
        SeaStateResponse r;
        {
          py::gil_scoped_release released;
          r = seaStateResponse(scenario, cable_out);
        }
        py::dict components, deviation;
        std::vector<double> frequency, encounter, direction, amplitude;
        for (const SeaStateComponent& c : r.components)
        {
          frequency.push_back(c.frequency);
          encounter.push_back(c.encounter_frequency);
          direction.push_back(c.direction);
          amplitude.push_back(c.amplitude);
        }
        components["frequency"] = py::array(py::cast(frequency));
        components["encounter_frequency"] = py::array(py::cast(encounter));
        components["direction"] = py::array(py::cast(direction));
        components["amplitude"] = py::array(py::cast(amplitude));
        for (int j = 0; j < kSeaStateOutputs; ++j)
        {
          std::vector<std::complex<double>> values;
          for (const SeaStateComponent& c : r.components)
            values.push_back(c.outputs[j]);
          components[SeaStateResponse::names[j]] = py::array(py::cast(values));
          deviation[SeaStateResponse::names[j]] = r.standard_deviation[j];
        }
        return py::dict("speed"_a = r.speed, "components"_a = components, "standard_deviation"_a = deviation);
      },
      "scenario"_a, "cable_out"_a = py::none(),
      "The steady tow in the scenario's sea, in the frequency domain (tow_sim_response --scenario): {'speed', "
      "'components': per wave component frequency, encounter_frequency [rad/s], direction [rad, relative to the "
      "heading], amplitude [m] and the outputs' complex amplitudes per metre of wave, 'standard_deviation': per "
      "output}.");
}
}  // namespace
}  // namespace tow_sim::python

PYBIND11_MODULE(_core, m)
{
  m.doc() = "tow_sim's ROS-free core: configurations, scenarios, runs, steady tows and towing charts.";
  // pybind11 looks NumPy's C API up once, on the first array made (a function-local static that imports numpy).
  // Made here, under the import's lock: two threads whose runs made their first arrays at once deadlocked, one
  // holding the GIL and waiting for the static, the other inside the static waiting for the GIL to import numpy.
  const pybind11::array_t<double> first_array(0);
  tow_sim::python::bindConfig(m);
  tow_sim::python::bindScenario(m);
  tow_sim::python::bindSnapshot(m);
  tow_sim::python::bindRun(m);
  tow_sim::python::bindSteadyTow(m);
  tow_sim::python::bindChart(m);
  tow_sim::python::bindPlan(m);
  tow_sim::python::bindModes(m);
  tow_sim::python::bindResponse(m);
  tow_sim::python::bindStrumming(m);
  tow_sim::python::bindSeaState(m);
}
