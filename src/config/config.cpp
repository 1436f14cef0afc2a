#include "tow_sim/config/config.h"

#include "tow_sim/config/yaml_section.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tow_sim
{
namespace
{
using detail::fail;
using detail::Section;

void readCable(Section s, CableParams& c)
{
  s.read("length", c.length);
  s.read("segments", c.segments);
  s.read("diameter", c.diameter);
  s.read("mass_per_length", c.mass_per_length);
  s.read("normal_drag_coefficient", c.normal_drag_coefficient);
  s.read("tangential_drag_coefficient", c.tangential_drag_coefficient);
  s.read("c1", c.c1);
  s.read("c2", c.c2);
  s.read("added_mass_coefficient", c.added_mass_coefficient);
  const std::string model = s.text("tangential_drag_model", "pode");
  if (model == "pode")
    c.tangential_drag_model = TangentialDragModel::kPode;
  else if (model == "quadratic")
    c.tangential_drag_model = TangentialDragModel::kQuadratic;
  else
    fail(s.path("tangential_drag_model"), "= '" + model + "' must be 'pode' or 'quadratic'");
  s.finish();
}

void readEnvironment(Section s, Environment& e)
{
  s.read("gravity", e.gravity);
  s.read("water_density", e.water_density);
  s.read("current", e.current_W);
  e.current_profile.clear();
  for (Section item : s.items("current_profile"))
  {
    CurrentSample sample;
    item.read("depth", sample.depth);
    item.read("velocity", sample.velocity_W);
    item.finish();
    e.current_profile.push_back(sample);
  }
  s.finish();
}

void readNumerics(Section s, NumericsParams& n)
{
  const std::string stepper = s.text("stepper", "dopri5");
  if (stepper == "dopri5")
    n.stepper = StepperType::kDopri5;
  else if (stepper == "rk4")
    n.stepper = StepperType::kRk4;
  else
    fail(s.path("stepper"), "= '" + stepper + "' must be 'dopri5' or 'rk4'");
  s.read("abs_tol", n.abs_tol);
  s.read("rel_tol", n.rel_tol);
  s.read("max_step", n.max_step);
  s.read("fixed_step", n.fixed_step);
  s.read("tangential_smoothing_speed", n.tangential_smoothing_speed);
  s.finish();
}

void readWinch(Section s, WinchParams& w)
{
  s.read("enabled", w.enabled);
  s.read("min_length", w.min_length);
  s.read("max_length", w.max_length);
  s.read("max_rate", w.max_rate);
  s.read("max_acceleration", w.max_acceleration);
  s.read("response_time", w.response_time);
  s.read("segment_min_fraction", w.segment_min_fraction);
  s.read("segment_max_fraction", w.segment_max_fraction);
  s.finish();
}

void readSeabed(Section s, SeabedParams& b, const std::string& base_dir)
{
  const std::string type = s.text("type", "none");
  if (type == "none")
    b.type = SeabedParams::Type::kNone;
  else if (type == "flat")
    b.type = SeabedParams::Type::kFlat;
  else if (type == "grid")
    b.type = SeabedParams::Type::kGrid;
  else
    fail(s.path("type"), "= '" + type + "' must be 'none', 'flat' or 'grid'");
  s.read("depth", b.depth);
  b.grid_file = s.text("grid_file", "");
  s.read("stiffness", b.stiffness);
  s.read("damping", b.damping);
  s.read("vehicle_stiffness", b.vehicle_stiffness);
  s.read("vehicle_damping", b.vehicle_damping);
  s.read("friction", b.friction);
  s.read("friction_speed", b.friction_speed);
  s.finish();
  if (b.type == SeabedParams::Type::kGrid)
  {
    if (b.grid_file.empty())
      fail(s.path("grid_file"), "must name a bathymetry file for type 'grid'");
    // Resolved to an absolute path, so a configuration written back (the batch runner's scenario.yaml,
    // in another folder) reads the same grid from anywhere.
    const std::string path = b.grid_file[0] == '/' ? b.grid_file : base_dir + b.grid_file;
    std::error_code no_cwd;
    const std::filesystem::path absolute = std::filesystem::absolute(path, no_cwd);
    b.grid_file = no_cwd ? path : absolute.lexically_normal().string();
    try
    {
      b.grid = loadBathymetryFile(b.grid_file);
    }
    catch (const std::invalid_argument& e)
    {
      fail(s.path("grid_file"), e.what());
    }
  }
}

AngleTable readTable(Section s, const AngleTable& fallback, bool odd)
{
  std::vector<double> angles = s.list("angles"), values = s.list("values");
  s.finish();
  if (angles.empty() && values.empty())
    return fallback;
  return AngleTable(angles, values, odd, s.name());
}

void readFins(Section s, FinPairParams& f)
{
  s.read("lift_constant", f.lift_constant);
  s.read("drag_constant", f.drag_constant);
  s.read("max_deflection", f.max_deflection);
  s.read("max_rate", f.max_rate);
  s.read("center_of_pressure_offset", f.center_of_pressure_offset);
  f.lift = readTable(s.child("lift_table"), f.lift, true);
  f.drag = readTable(s.child("drag_table"), f.drag, false);
  s.finish();
}

void readInertia(Section s, Eigen::Matrix3d& I)
{
  double xx = I(0, 0), yy = I(1, 1), zz = I(2, 2), xy = I(0, 1), xz = I(0, 2), yz = I(1, 2);
  s.read("xx", xx);
  s.read("yy", yy);
  s.read("zz", zz);
  s.read("xy", xy);
  s.read("xz", xz);
  s.read("yz", yz);
  s.finish();
  I << xx, xy, xz, xy, yy, yz, xz, yz, zz;
}

void readAddedMass(Section s, VehicleParams& v)
{
  const std::string approach = s.text("approach", v.added_mass_approach == AddedMassApproach::kA ? "A" : "B");
  if (approach == "A")
    v.added_mass_approach = AddedMassApproach::kA;
  else if (approach == "B")
    v.added_mass_approach = AddedMassApproach::kB;
  else
    fail(s.path("approach"), "= '" + approach + "' must be 'A' or 'B'");
  s.read("e", v.added_mass_a);
  s.read("munk_terms", v.munk_terms);
  const std::vector<double> m = s.list("matrix");
  if (m.size() == 36)
  {
    for (int i = 0; i < 36; ++i)
      v.added_mass_b(i / 6, i % 6) = m[i];
  }
  else if (m.size() == 21)
  {
    int k = 0;
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j, ++k)
        v.added_mass_b(i, j) = v.added_mass_b(j, i) = m[k];
  }
  else if (!m.empty())
  {
    fail(s.path("matrix"), "must hold 36 numbers (6x6, row by row) or 21 (its upper triangle, row by row); got " +
                               std::to_string(m.size()));
  }
  if (s.has("prolate_spheroid"))
  {
    Section p = s.child("prolate_spheroid");
    ProlateSpheroid ps;
    p.read("length", ps.length);
    p.read("diameter", ps.diameter);
    p.read("center_from_bail", ps.center_from_bail);
    p.finish();
    requireInRange(p.path("length"), ps.length, 0.0, 1e3, "[m]", true);
    requireInRange(p.path("diameter"), ps.diameter, 0.0, ps.length, "[m] (0 .. length: prolate)", true);
    if (!m.empty())
      fail(s.path("prolate_spheroid"), "give either matrix or prolate_spheroid, not both");
    v.prolate_spheroid = ps;
  }
  s.finish();
}

void readVehicle(Section s, VehicleParams& v)
{
  s.read("tail_from_bail", v.tail_from_bail);
  s.read("cg_from_bail", v.cg_from_bail);
  s.read("horizontal_fin_from_bail", v.horizontal_fin_from_bail);
  s.read("vertical_fin_from_bail", v.vertical_fin_from_bail);
  s.read("nose_from_bail", v.nose_from_bail);
  s.read("cb_from_bail", v.cb_from_bail);
  s.read("mass", v.mass);
  s.read("displaced_volume", v.displaced_volume);
  readInertia(s.child("inertia"), v.inertia_B);
  s.read("c1", v.c1);
  s.read("c2", v.c2);
  readAddedMass(s.child("added_mass"), v);
  s.read("max_thrust", v.max_thrust);
  s.read("thrust_offset_z", v.thrust_offset_z);
  readFins(s.child("rudder"), v.rudder);
  readFins(s.child("elevator"), v.elevator);
  s.finish();
}

YAML::Node tableYaml(const AngleTable& t)
{
  YAML::Node n;
  n["angles"] = t.angles();
  n["values"] = t.values();
  return n;
}

YAML::Node finsYaml(const FinPairParams& f)
{
  YAML::Node n;
  n["lift_constant"] = f.lift_constant;
  n["drag_constant"] = f.drag_constant;
  n["max_deflection"] = f.max_deflection;
  n["max_rate"] = f.max_rate;
  n["center_of_pressure_offset"] = f.center_of_pressure_offset;
  n["lift_table"] = tableYaml(f.lift);
  n["drag_table"] = tableYaml(f.drag);
  return n;
}
}  // namespace

SimulationConfig loadConfigUnguarded(const YAML::Node& root, const std::string& prefix, const std::string& base_dir);

std::string directoryOf(const std::string& path)
{
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

SimulationConfig loadConfig(const YAML::Node& root, const std::string& prefix, const std::string& base_dir)
{
  try
  {
    return loadConfigUnguarded(root, prefix, base_dir);
  }
  catch (const YAML::Exception& e)  // a shape the checks above did not foresee: still a clear refusal
  {
    throw std::invalid_argument((prefix.empty() ? std::string("configuration") : prefix) + ": " + e.what());
  }
}

SimulationConfig loadConfigUnguarded(const YAML::Node& root, const std::string& prefix, const std::string& base_dir)
{
  SimulationConfig c;
  if (root && !root.IsNull() && !root.IsMap())
    fail(prefix.empty() ? "configuration" : prefix,
         "must be a mapping with the sections cable, vehicle, environment, "
         "numerics");
  auto section = [&](const char* name)
  { return Section(root && root.IsMap() ? root[name] : YAML::Node(), prefix + name); };
  readCable(section("cable"), c.cable);
  readEnvironment(section("environment"), c.environment);
  readNumerics(section("numerics"), c.numerics);
  readVehicle(section("vehicle"), c.vehicle);
  readWinch(section("winch"), c.winch);
  readSeabed(section("seabed"), c.seabed, base_dir);
  validate(c.cable, prefix + "cable");
  validate(c.environment, prefix + "environment");
  validate(c.numerics, prefix + "numerics");
  validate(c.vehicle, prefix + "vehicle");
  validate(c.winch, c.cable, prefix + "winch");
  validate(c.seabed, prefix + "seabed");
  return c;
}

SimulationConfig loadConfigFile(const std::string& path)
{
  YAML::Node root;
  try
  {
    root = YAML::LoadFile(path);
  }
  catch (const YAML::Exception& e)
  {
    throw std::invalid_argument(path + ": cannot read the configuration: " + e.what());
  }
  return loadConfig(root, "", directoryOf(path));
}

YAML::Node toYaml(const SimulationConfig& c)
{
  YAML::Node root;
  YAML::Node cable = root["cable"];
  cable["length"] = c.cable.length;
  cable["segments"] = c.cable.segments;
  cable["diameter"] = c.cable.diameter;
  cable["mass_per_length"] = c.cable.mass_per_length;
  cable["normal_drag_coefficient"] = c.cable.normal_drag_coefficient;
  cable["tangential_drag_coefficient"] = c.cable.tangential_drag_coefficient;
  if (c.cable.c1)
    cable["c1"] = *c.cable.c1;
  if (c.cable.c2)
    cable["c2"] = *c.cable.c2;
  cable["added_mass_coefficient"] = c.cable.added_mass_coefficient;
  cable["tangential_drag_model"] = c.cable.tangential_drag_model == TangentialDragModel::kPode ? "pode" : "quadratic";

  YAML::Node env = root["environment"];
  env["gravity"] = c.environment.gravity;
  env["water_density"] = c.environment.water_density;
  env["current"] =
      std::vector<double>{ c.environment.current_W.x(), c.environment.current_W.y(), c.environment.current_W.z() };
  env["current_profile"] = YAML::Node(YAML::NodeType::Sequence);
  for (const CurrentSample& sample : c.environment.current_profile)
  {
    YAML::Node item;
    item["depth"] = sample.depth;
    item["velocity"] = std::vector<double>{ sample.velocity_W.x(), sample.velocity_W.y(), sample.velocity_W.z() };
    env["current_profile"].push_back(item);
  }

  YAML::Node winch = root["winch"];
  winch["enabled"] = c.winch.enabled;
  winch["min_length"] = c.winch.min_length;
  winch["max_length"] = c.winch.max_length;
  winch["max_rate"] = c.winch.max_rate;
  winch["max_acceleration"] = c.winch.max_acceleration;
  winch["response_time"] = c.winch.response_time;
  winch["segment_min_fraction"] = c.winch.segment_min_fraction;
  winch["segment_max_fraction"] = c.winch.segment_max_fraction;

  YAML::Node bed = root["seabed"];
  const SeabedParams& b = c.seabed;
  bed["type"] = b.type == SeabedParams::Type::kNone ? "none" : (b.type == SeabedParams::Type::kFlat ? "flat" : "grid");
  bed["depth"] = b.depth;
  bed["grid_file"] = b.grid_file;
  bed["stiffness"] = b.stiffness;
  bed["damping"] = b.damping;
  bed["vehicle_stiffness"] = b.vehicle_stiffness;
  bed["vehicle_damping"] = b.vehicle_damping;
  bed["friction"] = b.friction;
  bed["friction_speed"] = b.friction_speed;

  YAML::Node num = root["numerics"];
  num["stepper"] = c.numerics.stepper == StepperType::kDopri5 ? "dopri5" : "rk4";
  num["abs_tol"] = c.numerics.abs_tol;
  num["rel_tol"] = c.numerics.rel_tol;
  num["max_step"] = c.numerics.max_step;
  num["fixed_step"] = c.numerics.fixed_step;
  num["tangential_smoothing_speed"] = c.numerics.tangential_smoothing_speed;

  const VehicleParams& v = c.vehicle;
  YAML::Node veh = root["vehicle"];
  veh["tail_from_bail"] = v.tail_from_bail;
  veh["cg_from_bail"] = v.cg_from_bail;
  veh["horizontal_fin_from_bail"] = v.horizontal_fin_from_bail;
  veh["vertical_fin_from_bail"] = v.vertical_fin_from_bail;
  veh["nose_from_bail"] = v.nose_from_bail;
  veh["cb_from_bail"] = v.cb_from_bail;
  veh["mass"] = v.mass;
  veh["displaced_volume"] = v.displaced_volume;
  YAML::Node inertia = veh["inertia"];
  inertia["xx"] = v.inertia_B(0, 0);
  inertia["yy"] = v.inertia_B(1, 1);
  inertia["zz"] = v.inertia_B(2, 2);
  inertia["xy"] = v.inertia_B(0, 1);
  inertia["xz"] = v.inertia_B(0, 2);
  inertia["yz"] = v.inertia_B(1, 2);
  veh["c1"] = v.c1;
  veh["c2"] = v.c2;
  YAML::Node am = veh["added_mass"];
  am["approach"] = v.added_mass_approach == AddedMassApproach::kA ? "A" : "B";
  am["e"] = v.added_mass_a;
  am["munk_terms"] = v.munk_terms;
  if (v.prolate_spheroid)
  {
    am["prolate_spheroid"]["length"] = v.prolate_spheroid->length;
    am["prolate_spheroid"]["diameter"] = v.prolate_spheroid->diameter;
    am["prolate_spheroid"]["center_from_bail"] = v.prolate_spheroid->center_from_bail;
  }
  else
  {
    std::vector<double> m(v.added_mass_b.data(), v.added_mass_b.data() + 36);  // symmetric: order immaterial
    am["matrix"] = m;
  }
  veh["max_thrust"] = v.max_thrust;
  veh["thrust_offset_z"] = v.thrust_offset_z;
  veh["rudder"] = finsYaml(v.rudder);
  veh["elevator"] = finsYaml(v.elevator);
  return root;
}

}  // namespace tow_sim
