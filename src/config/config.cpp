#include "tow_sim/config/config.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tow_sim/config/node_params.h"
#include "tow_sim/config/param_yaml.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/core/integration/winch.h"
#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
using detail::fail;
using detail::ParamReader;
using detail::Section;

// The keys a table cannot read on its own: lists, tables, the added-mass matrix, the grid file.

void readCurrentProfile(Section& s, Environment& e)
{
  e.current_profile.clear();
  for (Section item : s.items("current_profile"))
  {
    CurrentSample sample;
    item.read("depth", sample.depth);
    item.read("velocity", sample.velocity_W);
    item.finish();
    e.current_profile.push_back(sample);
  }
}

// cable.loading: "bare" or {angles, normal, tangential, lift}; left out, the level above's (`cable`).
void readLoading(Section& s, CableParams& c)
{
  if (!s.has("loading"))
    return;
  if (s.isScalar("loading"))
  {
    const std::string text = s.text("loading", "bare");
    if (text != "bare")
      fail(s.path("loading"), "must be bare or a mapping {angles, normal, tangential, lift}; got '" + text + "'");
    c.loading.reset();
    return;
  }
  Section table = s.child("loading");
  std::vector<double> angles = table.list("angles"), normal = table.list("normal"),
                      tangential = table.list("tangential"), lift = table.list("lift");
  table.finish();
  c.loading = std::make_shared<const CableLoading>(angles, normal, tangential, lift, table.name());
}

// cable.sections: each entry the cable's keys, those left out the cable level's (read before); length and
// segments required. The cable level's length and segments, when left out, are the sections' sums.
void readSections(Section& s, SimulationConfig& c)
{
  c.sections.clear();
  for (Section item : s.items("sections"))
  {
    if (item.has("depressor"))  // {depressor: {...}} alone: one rigid element, the cable level's keys unused
    {
      CableParams section = c.cable;
      section.depressor = DepressorParams();
      Section body = item.child("depressor");
      ParamReader r(body);
      r.read(depressorParams(), *section.depressor);
      r.finish();
      item.finish();  // nothing beside it
      section.length = section.depressor->length;
      section.segments = 1;
      section.axial_stiffness.reset();  // refused below when the cable is elastic
      if (c.cable.elastic())
        fail(item.path("depressor"), "is a rigid element: not in an elastic cable (cable.axial_stiffness set)");
      section.bending_stiffness = 0.0;  // universal joints at both ends
      section.loading.reset();          // its own body's drag
      section.strumming = StrummingLaw::kNone;
      section.diameter = std::min(1.0, section.depressor->diameter);  // drawn at its body's width
      validate(section, item.name());
      c.sections.push_back(section);
      continue;
    }
    for (const char* key : { "length", "segments" })
      if (!item.has(key))
        fail(item.path(key), "is required in each section");
    for (const char* key : { "safe_working_load", "breaking_load", "break_at_breaking_load" })
      if (item.has(key))
        fail(item.path(key), std::string("is the whole cable's: set it at ") + s.path(key));
    for (const char* key : { "sections", "bodies" })
      if (item.has(key))
        fail(item.path(key), "sections do not nest: give every section and every body at " + s.path(key));
    CableParams section = c.cable;
    ParamReader r(item);
    r.read(cableParams(), section);
    readLoading(r.at(""), section);
    r.finish();
    validate(section, item.name());
    c.sections.push_back(section);
  }
  if (c.sections.empty())
    return;
  double length = 0.0;
  int segments = 0;
  for (const CableParams& section : c.sections)
  {
    length += section.length;
    segments += section.segments;
  }
  if (!s.has("length"))
    c.cable.length = length;
  if (!s.has("segments"))
    c.cable.segments = segments;
}

// cable.bodies: {at, mass, displaced_volume, drag_area, added_mass}; `at` required.
void readBodies(Section& s, SimulationConfig& c)
{
  c.bodies.clear();
  for (Section item : s.items("bodies"))
  {
    CableBodyParams b;
    if (!item.has("at"))
      fail(item.path("at"), "is required: the body's distance from the tow point along the cable [m]");
    item.read("at", b.at);
    item.read("mass", b.body.mass);
    item.read("displaced_volume", b.body.displaced_volume);
    item.read("drag_area", b.body.drag_area);
    item.read("added_mass", b.body.added_mass);
    item.finish();
    requireInRange(item.path("at"), b.at, 0.0, 1e5, "[m] (from the tow point along the cable)", kOpen);
    requireInRange(item.path("mass"), b.body.mass, 0.0, 1e7, "[kg]");
    requireInRange(item.path("displaced_volume"), b.body.displaced_volume, 0.0, 1e4, "[m^3]");
    requireInRange(item.path("drag_area"), b.body.drag_area, 0.0, 1e3, "[m^2] (C_D A)");
    requireInRange(item.path("added_mass"), b.body.added_mass, 0.0, 1e7, "[kg]");
    c.bodies.push_back(b);
  }
}

}  // namespace

std::string resolvePath(const std::string& file, const std::string& base_dir)
{
  const std::string path = file[0] == '/' ? file : base_dir + file;
  std::error_code no_cwd;
  const std::filesystem::path absolute = std::filesystem::absolute(path, no_cwd);
  return no_cwd ? path : absolute.lexically_normal().string();
}

namespace
{
void readGrid(Section& s, SeabedParams& b, const std::string& base_dir)
{
  if (b.type != SeabedParams::Type::kGrid)
    return;
  if (b.grid_file.empty())
    fail(s.path("grid_file"), "must name a bathymetry file for type 'grid'");
  b.grid_file = resolvePath(b.grid_file, base_dir);
  try
  {
    b.grid = loadBathymetryFile(b.grid_file);
  }
  catch (const std::invalid_argument& e)
  {
    fail(s.path("grid_file"), e.what());
  }
}

AngleTable readAngleTable(Section s, const AngleTable& fallback, bool odd)
{
  std::vector<double> angles = s.list("angles"), values = s.list("values");
  s.finish();
  if (angles.empty() && values.empty())
    return fallback;
  return AngleTable(angles, values, odd, s.name());
}

void readAddedMassMatrix(Section& s, VehicleParams& v)
{
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
  if (!s.has("prolate_spheroid"))
    return;
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

void readVehicle(ParamReader& r, VehicleParams& v)
{
  r.read(vehicleParams(), v);
  readAddedMassMatrix(r.at("added_mass"), v);
  for (const char* pair : { "rudder", "elevator" })
  {
    FinPairParams& f = std::string(pair) == "rudder" ? v.rudder : v.elevator;
    f.lift = readAngleTable(r.at(pair).child("lift_table"), f.lift, true);
    f.drag = readAngleTable(r.at(pair).child("drag_table"), f.drag, false);
  }
}

YAML::Node angleTableYaml(const AngleTable& t)
{
  YAML::Node n;
  n["angles"] = t.angles();
  n["values"] = t.values();
  return n;
}

void writeVehicleExtras(YAML::Node veh, const VehicleParams& v)
{
  YAML::Node am = veh["added_mass"];
  if (v.prolate_spheroid)
  {
    am["prolate_spheroid"]["length"] = v.prolate_spheroid->length;
    am["prolate_spheroid"]["diameter"] = v.prolate_spheroid->diameter;
    am["prolate_spheroid"]["center_from_bail"] = v.prolate_spheroid->center_from_bail;
  }
  else
  {
    am["matrix"] = std::vector<double>(v.added_mass_b.data(), v.added_mass_b.data() + 36);  // symmetric
  }
  for (const char* pair : { "rudder", "elevator" })
  {
    const FinPairParams& f = std::string(pair) == "rudder" ? v.rudder : v.elevator;
    veh[pair]["lift_table"] = angleTableYaml(f.lift);
    veh[pair]["drag_table"] = angleTableYaml(f.drag);
  }
}

SimulationConfig loadConfigUnguarded(const YAML::Node& root, const std::string& prefix, const std::string& base_dir)
{
  SimulationConfig c;
  if (root && !root.IsNull() && !root.IsMap())
    fail(prefix.empty() ? "configuration" : prefix,
         "must be a mapping with the sections cable, vehicle, environment, numerics, winch, seabed");
  auto section = [&](const char* name)
  { return ParamReader(Section(root && root.IsMap() ? root[name] : YAML::Node(), prefix + name)); };
  ParamReader cable = section("cable"), environment = section("environment"), numerics = section("numerics"),
              vehicle = section("vehicle"), winch = section("winch"), seabed = section("seabed");
  cable.read(cableParams(), c.cable);
  readLoading(cable.at(""), c.cable);
  readSections(cable.at(""), c);
  readBodies(cable.at(""), c);
  environment.read(environmentParams(), c.environment);
  readCurrentProfile(environment.at(""), c.environment);
  numerics.read(numericsParams(), c.numerics);
  readVehicle(vehicle, c.vehicle);
  winch.read(winchParams(), c.winch);
  seabed.read(seabedParams(), c.seabed);
  for (const ParamReader* r : { &cable, &environment, &numerics, &vehicle, &winch, &seabed })
    r->finish();
  readGrid(seabed.at(""), c.seabed, base_dir);
  validate(c.cable, prefix + "cable");
  validate(c.environment, prefix + "environment");
  validate(c.numerics, prefix + "numerics");
  validate(c.vehicle, prefix + "vehicle");
  validateSectionsAndBodies(c, prefix);
  validate(c.winch, cableSections(c), prefix + "winch");
  validate(c.seabed, prefix + "seabed");
  return c;
}
}  // namespace

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
  catch (const YAML::Exception& e)  // a shape the checks did not foresee: still a clear refusal
  {
    throw std::invalid_argument((prefix.empty() ? std::string("configuration") : prefix) + ": " + e.what());
  }
}

std::vector<std::string> configurationFileKeys()
{
  std::vector<std::string> keys = { "cable",  "vehicle",       "environment", "numerics", "winch",
                                    "seabed", "sensor_frames", "nav",         "sensors" };
  for (const std::string& key : topLevelKeys(nodeParams()))
    keys.push_back(key);
  return keys;
}

void requireKnownKeys(const YAML::Node& root, const std::string& prefix, const std::vector<std::string>& known)
{
  // "/tow_sim/" names its keys "/tow_sim.key" here (ros_conv::withSlashes makes them "/tow_sim/key").
  Section top(root, prefix.empty() || prefix.back() != '/' ? prefix : prefix.substr(0, prefix.size() - 1));
  top.allow(known);
  top.finish();
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
  SimulationConfig config = loadConfig(root, "", directoryOf(path));
  try
  {
    requireKnownKeys(root, "", configurationFileKeys());
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(path + ": " + e.what());
  }
  return config;
}

YAML::Node loadingYaml(const CableParams& c)
{
  if (!c.loading)
    return YAML::Node("bare");
  YAML::Node n;
  n["angles"] = c.loading->angles();
  n["normal"] = c.loading->normal();
  n["tangential"] = c.loading->tangential();
  n["lift"] = c.loading->lift();
  return n;
}

YAML::Node toYaml(const SimulationConfig& c)
{
  YAML::Node root;
  detail::writeParams(root["cable"], cableParams(), c.cable);
  if (c.cable.loading)  // written only where set, so that the configurations before it read the same
    root["cable"]["loading"] = loadingYaml(c.cable);
  root["cable"]["sections"] = YAML::Node(YAML::NodeType::Sequence);
  for (const CableParams& section : c.sections)
  {
    YAML::Node item(YAML::NodeType::Map);
    if (section.depressor)
    {
      detail::writeParams(item["depressor"], depressorParams(), *section.depressor);
      root["cable"]["sections"].push_back(item);
      continue;
    }
    detail::writeParams(item, cableParams(), section);
    if (section.loading || c.cable.loading)
      item["loading"] = loadingYaml(section);
    for (const char* key : { "safe_working_load", "breaking_load", "break_at_breaking_load" })
      item.remove(key);
    root["cable"]["sections"].push_back(item);
  }
  root["cable"]["bodies"] = YAML::Node(YAML::NodeType::Sequence);
  for (const CableBodyParams& b : c.bodies)
  {
    YAML::Node item;
    item["at"] = b.at;
    item["mass"] = b.body.mass;
    item["displaced_volume"] = b.body.displaced_volume;
    item["drag_area"] = b.body.drag_area;
    item["added_mass"] = b.body.added_mass;
    root["cable"]["bodies"].push_back(item);
  }
  detail::writeParams(root["environment"], environmentParams(), c.environment);
  root["environment"]["current_profile"] = YAML::Node(YAML::NodeType::Sequence);
  for (const CurrentSample& sample : c.environment.current_profile)
  {
    YAML::Node item;
    item["depth"] = sample.depth;
    item["velocity"] = std::vector<double>{ sample.velocity_W.x(), sample.velocity_W.y(), sample.velocity_W.z() };
    root["environment"]["current_profile"].push_back(item);
  }
  detail::writeParams(root["winch"], winchParams(), c.winch);
  detail::writeParams(root["seabed"], seabedParams(), c.seabed);
  detail::writeParams(root["numerics"], numericsParams(), c.numerics);
  detail::writeParams(root["vehicle"], vehicleParams(), c.vehicle);
  writeVehicleExtras(root["vehicle"], c.vehicle);
  return root;
}

}  // namespace tow_sim
