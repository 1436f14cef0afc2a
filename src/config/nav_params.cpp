#include "tow_sim/config/nav_params.h"

#include "tow_sim/config/param_yaml.h"

namespace tow_sim
{
TowNavParams loadNavParams(const YAML::Node& root, const std::string& prefix)
{
  TowNavParams params;
  detail::Section top(root, prefix);
  top.read("tow_point", params.tow_point_S);
  detail::ParamReader reader(top.child("nav"));
  reader.read(towNavParams(), params);
  reader.finish();
  validate(params, reader.at("").name());
  return params;
}

SurveySensorParams loadSensorParams(const YAML::Node& root, const std::string& prefix)
{
  SurveySensorParams params;
  detail::Section top(root, prefix);
  if (!top.has("sensors"))
    return params;
  params.enabled = true;
  detail::ParamReader reader(top.child("sensors"));
  reader.read(surveySensorParams(), params);
  reader.finish();
  validate(params, reader.at("").name());
  return params;
}

}  // namespace tow_sim
