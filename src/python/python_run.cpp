#include "python_run.h"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "convert.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace tow_sim::python
{
namespace
{
Scenario straightCourse(const SimulationConfig& config, double speed, double heading, double duration,
                        const Eigen::Vector3d& tow_point_S, const std::vector<CommandEvent>& commands)
{
  if (!(duration > 0.0 && duration <= 1e6))
    throw std::invalid_argument("duration = " + std::to_string(duration) + " s is out of range: must be in (0, 1e6]");
  if (!(std::abs(speed) <= 20.0))
    throw std::invalid_argument("speed = " + std::to_string(speed) + " m/s is out of range: must be in [-20, 20]");
  if (!std::isfinite(heading) || !tow_point_S.allFinite())
    throw std::invalid_argument("heading and tow_point must be finite");
  Scenario sc;
  sc.config = config;
  sc.tow_point_S = tow_point_S;
  sc.start_heading = heading;
  Manoeuvre straight;
  straight.type = Manoeuvre::Type::kStraight;
  straight.speed = speed;
  straight.duration = duration;
  sc.manoeuvres = { straight };
  sc.duration = duration;
  sc.commands = commands;
  std::sort(sc.commands.begin(), sc.commands.end(),
            [](const CommandEvent& a, const CommandEvent& b) { return a.t < b.t; });
  return sc;
}

StartedScenario sampledShip(const std::vector<double>& t, const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& v,
                            const std::vector<double>& heading)
{
  const size_t n = t.size();
  if (n < 2 || static_cast<size_t>(p.rows()) != n || static_cast<size_t>(v.rows()) != n || heading.size() != n)
    throw std::invalid_argument(
        "ship: t, tow_point, velocity and heading need the same number (>= 2) of samples, got " + std::to_string(n) +
        ", " + std::to_string(p.rows()) + ", " + std::to_string(v.rows()) + ", " + std::to_string(heading.size()));
  StartedScenario r;
  r.ship = std::make_shared<ShipHistory>(1.0, std::max<size_t>(400, n + 1));
  for (size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d p_i = p.row(static_cast<Eigen::Index>(i)), v_i = v.row(static_cast<Eigen::Index>(i));
    ShipPose pose{ p_i.x(), p_i.y(), heading[i], v_i.head<2>().norm(), p_i.z() };
    if (!r.ship->add(t[i], p_i, v_i, pose))
      throw std::invalid_argument("ship sample " + std::to_string(i) + " (t = " + std::to_string(t[i]) +
                                  " s): times must increase strictly and every value be finite");
  }
  return r;
}
}  // namespace

PythonRun::PythonRun(const Scenario& scenario) : run_(startScenario(scenario)), end_(scenario.duration) {}

PythonRun::PythonRun(const SimulationConfig& config, double speed, double heading, double duration,
                     const Eigen::Vector3d& tow_point_S, const std::vector<CommandEvent>& commands)
    : PythonRun(straightCourse(config, speed, heading, duration, tow_point_S, commands))
{
}

PythonRun::PythonRun(const SimulationConfig& config, const std::vector<double>& t, const Eigen::MatrixX3d& position,
                     const Eigen::MatrixX3d& velocity, const std::vector<double>& heading,
                     const std::vector<CommandEvent>& commands)
    : run_(sampledShip(t, position, velocity, heading)), end_(t.back())
{
  run_.run = std::make_unique<TowRun>(config, run_.ship);
  run_.run->schedule(commands);
  run_.start_warning = run_.run->start(t.front());
}

void PythonRun::addShipSample(double t, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double heading)
{
  if (!run_.ship->add(t, p_W, v_W, ShipPose{ p_W.x(), p_W.y(), heading, v_W.head<2>().norm(), p_W.z() }))
    throw std::invalid_argument("add_ship_sample: t = " + std::to_string(t) + " s must be after the newest sample (" +
                                std::to_string(end_) + " s) and every value finite");
  end_ = t;
}

void PythonRun::requireWithinTrack(double t) const
{
  if (t > end_ + 1e-9 * std::max(1.0, end_))
  {
    std::ostringstream os;
    os.precision(10);
    os << "t = " << t << " s is past the end of the ship's track (" << end_
       << " s: the scenario's duration, or the newest ship sample)";
    throw std::invalid_argument(os.str());
  }
}

void PythonRun::advanceTo(double t)
{
  requireWithinTrack(t);
  run_.run->advanceTo(t);
}

TowSnapshot PythonRun::snapshot()
{
  return run_.run->snapshot();
}

std::vector<std::vector<double>> PythonRun::run(double until, double every)
{
  if (!(every > 0.0 && std::isfinite(every)))
    throw std::invalid_argument("every = " + std::to_string(every) + " s: must be > 0");
  requireWithinTrack(until);
  if (!(until >= tow().time()))
    throw std::invalid_argument("until = " + std::to_string(until) + " s is before the run's time " +
                                std::to_string(tow().time()) + " s");
  std::vector<std::vector<double>> rows;
  const long last = std::lround(until / every);
  for (long i = static_cast<long>(std::ceil(tow().time() / every - 1e-9)); i <= last; ++i)
  {
    const double t = std::min(until, i * every);  // as runScenario's output times
    if (t <= last_output_)
      continue;
    run_.run->advanceTo(t);
    rows.push_back(timeseriesValues(run_.run->snapshot()));
    last_output_ = t;
  }
  return rows;
}
}  // namespace tow_sim::python

namespace tow_sim::python
{
namespace
{
py::dict runSeries(PythonRun& r, double until, double every)
{
  std::vector<std::vector<double>> rows;
  {
    py::gil_scoped_release released;
    rows = r.run(until, every);
  }
  return seriesDict(r.header(), rows);
}

std::unique_ptr<PythonRun> fromConfig(const SimulationConfig& c, double speed, double heading, double duration,
                                      const py::object& tow_point, const py::object& commands, const py::object& ship)
{
  const std::vector<CommandEvent> events = commandList(commands);
  if (ship.is_none())
    return std::make_unique<PythonRun>(c, speed, heading, duration, vector3(tow_point, "tow_point"), events);
  const char* form = " (arrays t [s], tow_point (n, 3) [m], velocity (n, 3) [m/s], heading [rad])";
  if (!py::isinstance<py::dict>(ship))
    throw std::invalid_argument(std::string("ship: must be a dict") + form);
  const py::dict d = ship.cast<py::dict>();
  for (const char* key : { "t", "tow_point", "velocity", "heading" })
    if (!d.contains(key))
      throw std::invalid_argument(std::string("ship: needs the key '") + key + "'" + form);
  try
  {
    return std::make_unique<PythonRun>(c, d["t"].cast<std::vector<double>>(), d["tow_point"].cast<Eigen::MatrixX3d>(),
                                       d["velocity"].cast<Eigen::MatrixX3d>(), d["heading"].cast<std::vector<double>>(),
                                       events);
  }
  catch (const py::cast_error&)
  {
    throw std::invalid_argument(std::string("ship: a value is not an array of numbers of its shape") + form);
  }
}
}  // namespace

void bindRun(py::module_& m)
{
  py::class_<PythonRun>(m, "Run", "A tow run: step it, command it, read its outputs.")
      .def(py::init<const Scenario&>(), "scenario"_a, "The scenario's run as tow_sim_batch runs it.")
      .def(py::init(&fromConfig), "config"_a, "speed"_a = 2.0, "heading"_a = 0.0, "duration"_a = 3600.0,
           "tow_point"_a = py::make_tuple(-20.0, 0.0, 0.0), "commands"_a = py::none(), "ship"_a = py::none(),
           "The configuration behind a ship on a straight course (speed [m/s], heading [rad] from +x, for duration "
           "[s], the tow point [m] in the ship frame), or behind the tow point given by `ship` = {t, tow_point, "
           "velocity, heading} arrays (world); commands: a list of {t, rudder, elevator, thrust, payout_rate, "
           "differential}.")
      .def("advance_to", &PythonRun::advanceTo, "t"_a, py::call_guard<py::gil_scoped_release>(),
           "Integrates to t [s] (RuntimeError on divergence: the last good state stays).")
      .def("snapshot", &PythonRun::snapshot, "Every output now (the length-error maximum starts again).")
      .def("run", &runSeries, "until"_a, "every"_a = 1.0,
           "Advances to `until` [s], returning timeseries.csv's columns at every `every` [s] (dict of arrays).")
      .def(
          "set_fins",
          [](PythonRun& r, double rudder, double elevator, double thrust, double differential)
          { return r.tow().command(rudder, elevator, thrust, differential); },
          "rudder"_a = 0.0, "elevator"_a = 0.0, "thrust"_a = 0.0, "differential"_a = 0.0,
          "Fin angles [rad] and thrust [N] from now on, and the elevator's differential [rad] (starboard fin +, "
          "port fin -; rolls a vehicle with vehicle.roll: free); returns True when a value saturated.")
      .def(
          "set_winch", [](PythonRun& r, double rate) { return r.tow().setWinchCommand(rate); }, "rate"_a,
          "The winch's payout rate [m/s] (positive pays out; needs winch.enabled); returns the rate accepted.")
      .def(
          "set_current", [](PythonRun& r, const py::object& v) { r.tow().setCurrent(vector3(v, "current")); },
          "current"_a, "A uniform current [m/s], world ENU, from now on.")
      .def("add_ship_sample", &PythonRun::addShipSample, "t"_a, "tow_point"_a, "velocity"_a, "heading"_a,
           "Extends a sampled ship's track: the tow point [m], its velocity [m/s] (world) and heading [rad] at t [s].")
      .def_property_readonly(
          "time", [](PythonRun& r) { return r.tow().time(); }, "[s]")
      .def_property_readonly("end", &PythonRun::end, "[s] the ship's track ends here")
      .def_property_readonly("config", &PythonRun::config)
      .def_property_readonly("start_warning", &PythonRun::startWarning,
                             "the initial shape's fallback, if it had to fall back ('' otherwise)");
}

}  // namespace tow_sim::python
