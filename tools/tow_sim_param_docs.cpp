// tow_sim_param_docs: writes the parameter documentation generated from the parameter tables.
//   tow_sim_param_docs docs/parameters.md config/tow_sim.yaml           rewrite both in place
//   tow_sim_param_docs --check docs/parameters.md config/tow_sim.yaml   exit 1 if either is out of date
// The markdown file (any path; `make docs` gives docs/parameters.md): each table between <!-- params:NAME -->
// and <!-- /params -->; config/tow_sim.yaml: the whole file.
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>

#include "tow_sim/scenario/param_docs.h"

namespace
{
std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot read " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

int main(int argc, char** argv)
{
  const bool check = argc > 1 && !std::strcmp(argv[1], "--check");
  if (argc != (check ? 4 : 3))
  {
    std::fprintf(stderr, "usage: tow_sim_param_docs [--check] docs/parameters.md config/tow_sim.yaml\n");
    return 2;
  }
  const std::string docs_path = argv[check ? 2 : 1], config_path = argv[check ? 3 : 2];
  try
  {
    const std::string docs = readFile(docs_path), config = readFile(config_path);
    const std::string new_docs = tow_sim::withCurrentTables(docs), new_config = tow_sim::configFile();
    if (check)
    {
      const bool current = docs == new_docs && config == new_config;
      std::printf("%s\n", current ? "parameter documentation is current"
                                  : "parameter documentation is out of date: run make docs");
      return current ? 0 : 1;
    }
    std::ofstream(docs_path) << new_docs;
    std::ofstream(config_path) << new_config;
    std::printf("wrote %s and %s\n", docs_path.c_str(), config_path.c_str());
    return 0;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_param_docs: %s\n", e.what());
    return 2;
  }
}
