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

#include "cli.h"
#include "tow_sim/scenario/param_docs.h"

namespace
{
constexpr char kTool[] = "tow_sim_param_docs";
constexpr char kUsage[] = "tow_sim_param_docs [--check] DOCS.md CONFIG.yaml";
constexpr char kHelp[] = R"(
Writes the parameter documentation generated from the parameter tables: each table of DOCS.md
between <!-- params:NAME --> and <!-- /params --> and the whole of CONFIG.yaml (make docs gives it
docs/parameters.md and config/tow_sim.yaml).

Arguments:
  DOCS.md       the markdown file whose tables it rewrites (any path). Required.
  CONFIG.yaml   the configuration file it writes whole, every key with its unit. Required.
  --check       only checks: writes nothing, and says on stdout whether both files are current.
  -h, --help    prints this help and exits.

Output: DOCS.md and CONFIG.yaml rewritten in place (without --check).
Exit codes: 0 done (with --check: both files are current); 1 with --check: either is out of date
(run make docs); 2 bad arguments or a file that cannot be read.
)";

// "" or what is wrong with the arguments; check is --check's presence.
std::string parseArguments(int argc, char** argv, bool& check)
{
  check = argc > 1 && !std::strcmp(argv[1], "--check");
  for (int i = check ? 2 : 1; i < argc; ++i)
    if (argv[i][0] == '-')
      return std::string("unknown argument '") + argv[i] + "'";
  return argc == (check ? 4 : 3) ? "" : "needs the two files DOCS.md and CONFIG.yaml";
}

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
  if (tow_sim::cli::wantsHelp(argc, argv))
    return tow_sim::cli::printHelp(kUsage, kHelp);
  bool check = false;
  const std::string wrong = parseArguments(argc, argv, check);
  if (!wrong.empty())
    return tow_sim::cli::fail(kTool, kUsage, wrong);
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
