// libFuzzer target: any text fed to the configuration and scenario loaders either loads or is refused
// with std::invalid_argument (or a YAML parse error); nothing else escapes, nothing crashes.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "tow_sim/scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  YAML::Node root;
  try
  {
    root = YAML::Load(text);
  }
  catch (const YAML::Exception&)
  {
    return 0;
  }
  try
  {
    tow_sim::loadConfig(root);
  }
  catch (const std::invalid_argument&)
  {
  }
  try
  {
    const tow_sim::Scenario sc = tow_sim::loadScenario(root);
    tow_sim::toYaml(sc);
  }
  catch (const std::invalid_argument&)
  {
  }
  return 0;
}
