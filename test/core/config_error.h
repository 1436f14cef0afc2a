// What loadConfig says of a configuration text, for the tests of its refusals.
#pragma once

#include <yaml-cpp/yaml.h>
#include <stdexcept>
#include <string>

#include "tow_sim/config/config.h"

namespace tow_sim
{
namespace test
{
// The message loadConfig throws for `yaml` (read with `prefix`, as the node's parameter names), or
// "(accepted)" when it takes it.
inline std::string configError(const std::string& yaml, const std::string& prefix = "")
{
  try
  {
    loadConfig(YAML::Load(yaml), prefix);
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  return "(accepted)";
}
}  // namespace test
}  // namespace tow_sim
