// Every offline tool (tools/*.cpp) answers -h and --help: exit 0, the usage line first on stdout and every option
// its parser accepts explained on a line of its own; an unknown option exits 2 with a message on stderr that names
// it and points to --help (tools/cli.h). The options are listed here by hand from each tool's parser, so that an
// option missing from a help text fails this test.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace
{

struct Tool
{
  std::string name;
  std::vector<std::string> options;  // every option and argument its parser takes, as its help names them
};

const std::vector<Tool>& tools()
{
  static const std::vector<Tool> list = {
    { "tow_sim_batch", { "--scenario", "--out", "--precision" } },
    { "tow_sim_chart",
      { "--config", "--speeds", "--cable-out", "--current", "--out", "--no-plot", "--target-depth", "--speed",
        "--depth-band" } },
    { "tow_sim_demo", { "DURATION" } },
    { "tow_sim_modes", { "--config", "--speed", "--cable-out", "--count", "--out" } },
    { "tow_sim_nav", { "--config", "--measurements", "--bag", "--topics", "--nav-config", "--out" } },
    { "tow_sim_param_docs", { "--check", "DOCS.md", "CONFIG.yaml" } },
    { "tow_sim_response",
      { "--config", "--scenario", "--speed", "--cable-out", "--input", "--periods", "--tow-point", "--out" } },
    { "tow_sim_strumming", { "--config", "--speed", "--cable-out", "--current", "--bandwidth", "--out" } },
    { "tow_sim_urdf", { "CONFIG.yaml" } },
  };
  return list;
}

struct Outcome
{
  int status = -1;  // the exit status; -1 if the tool did not exit normally
  std::string out, err;
};

std::string readAll(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A folder for the tools' stdout and stderr, removed at exit.
struct OutputFolder
{
  std::string path;
  OutputFolder()
  {
    char name[] = "/tmp/tow_sim_tool_help.XXXXXX";
    path = mkdtemp(name) ? name : "";
  }
  ~OutputFolder()
  {
    std::error_code ignored;
    if (!path.empty())
      std::filesystem::remove_all(path, ignored);
  }
};

// Runs `program` with `arguments` (shell words), its stdout and stderr kept apart.
Outcome runProgram(const std::string& program, const std::string& arguments)
{
  static const OutputFolder folder;
  const std::string out = folder.path + "/out", err = folder.path + "/err";
  const int raw = std::system((program + " " + arguments + " > " + out + " 2> " + err).c_str());
  Outcome o;
  o.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  o.out = readAll(out);
  o.err = readAll(err);
  return o;
}

// Runs the tool, which is beside tow_sim_batch.
Outcome run(const std::string& tool, const std::string& arguments)
{
  const std::string batch = TOW_SIM_BATCH_BINARY;
  return runProgram(batch.substr(0, batch.rfind('/') + 1) + tool, arguments);
}

bool startsWith(const std::string& text, const std::string& start)
{
  return text.compare(0, start.size(), start) == 0;
}

TEST(ToolHelp, HelpPrintsTheUsageAndEveryOption)
{
  for (const Tool& tool : tools())
    for (const char* flag : { "--help", "-h" })
    {
      SCOPED_TRACE(tool.name + " " + flag);
      const Outcome o = run(tool.name, flag);
      EXPECT_EQ(o.status, 0) << o.err;
      EXPECT_TRUE(startsWith(o.out, "usage: " + tool.name)) << o.out;
      EXPECT_EQ(o.err, "");
      // Each option starts a line of its own, its explanation beside it.
      for (const std::string& option : tool.options)
        EXPECT_NE(o.out.find("\n  " + option + " "), std::string::npos) << option << " is not explained:\n" << o.out;
      EXPECT_NE(o.out.find("\n  -h, --help "), std::string::npos) << o.out;
      EXPECT_NE(o.out.find("Exit codes:"), std::string::npos) << o.out;
      std::istringstream lines(o.out);
      for (std::string line; std::getline(lines, line);)
        EXPECT_LE(line.size(), 100u) << "a line too long for a terminal: " << line;
    }
}

// --help anywhere wins over the other arguments: the help, exit 0, and nothing run.
TEST(ToolHelp, HelpAmongOtherArgumentsRunsNothing)
{
  for (const Tool& tool : tools())
  {
    SCOPED_TRACE(tool.name);
    const Outcome o = run(tool.name, "--config /no/such/file.yaml --help --out /no/such/folder");
    EXPECT_EQ(o.status, 0) << o.err;
    EXPECT_TRUE(startsWith(o.out, "usage: " + tool.name)) << o.out;
  }
}

TEST(ToolHelp, AnUnknownOptionIsRefusedNamingItAndPointingToHelp)
{
  for (const Tool& tool : tools())
  {
    SCOPED_TRACE(tool.name);
    const Outcome o = run(tool.name, "--no-such-option");
    EXPECT_EQ(o.status, 2);
    EXPECT_EQ(o.out, "");
    EXPECT_TRUE(startsWith(o.err, tool.name + ": ")) << o.err;
    EXPECT_NE(o.err.find("'--no-such-option'"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("\nusage: " + tool.name), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("Run '" + tool.name + " --help'"), std::string::npos) << o.err;
  }
}

// The rviz script answers --help without asking the master or starting rviz (it used to hand --help to rviz,
// which aborts without a display).
// An option given last without its value is named as such, not as an unknown argument.
TEST(ToolHelp, AnOptionWithoutItsValueSaysSo)
{
  const std::pair<std::string, std::string> cases[] = {
    { "tow_sim_batch", "--scenario" },   { "tow_sim_chart", "--config" },  { "tow_sim_modes", "--speed" },
    { "tow_sim_response", "--periods" }, { "tow_sim_strumming", "--out" }, { "tow_sim_nav", "--measurements" }
  };
  for (const auto& [tool, option] : cases)
  {
    const Outcome o = run(tool, option);
    EXPECT_EQ(o.status, 2) << tool;
    EXPECT_NE(o.err.find(option + " needs a value"), std::string::npos) << tool << ": " << o.err;
  }
}

TEST(ToolHelp, TheRvizScriptAnswersHelpWithoutStartingRviz)
{
  const Outcome o = runProgram("timeout 30 " + std::string(TOW_SIM_SOURCE_DIR) + "/scripts/tow_sim_rviz", "--help");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_TRUE(startsWith(o.out, "usage: tow_sim_rviz")) << o.out;
  EXPECT_NE(o.out.find("\n  TOW_SIM_NODE "), std::string::npos) << o.out;
  EXPECT_EQ(o.err, "");
}

// tow_sim_demo takes a number of seconds in range with nothing after it: it used to read "100abc" as 100.
TEST(ToolHelp, TheDemoRefusesADurationWithTrailingCharacters)
{
  for (const char* duration : { "100abc", "abc", "10", "2e6", "nan", "''" })
  {
    SCOPED_TRACE(duration);
    const Outcome o = run("tow_sim_demo", duration);
    EXPECT_EQ(o.status, 2);
    EXPECT_EQ(o.out, "");
    EXPECT_NE(o.err.find("is not a number of seconds in [60, 1e6]"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("Run 'tow_sim_demo --help'"), std::string::npos) << o.err;
  }
  const Outcome o = run("tow_sim_demo", "100abc");
  EXPECT_NE(o.err.find("duration: '100abc' is not a number of seconds in [60, 1e6]"), std::string::npos) << o.err;
  EXPECT_EQ(run("tow_sim_demo", "600 700").status, 2);
}

// An option the chosen form would ignore is refused, and an option that takes one number refuses a range: the
// planning forms of tow_sim_chart used to drop --out and --speeds, tow_sim_response to run the first of
// --speed 1:3:1's speeds only.
TEST(ToolHelp, AnOptionTheFormWouldIgnoreOrARangeForOneNumberIsRefused)
{
  const std::string config = " --config " + std::string(TOW_SIM_SOURCE_DIR) + "/config/tow_sim.yaml";
  const std::pair<std::string, std::string> cases[] = {
    { "tow_sim_chart" + config + " --target-depth 150 --speed 2 --out /tmp/x", "write no file" },
    { "tow_sim_chart" + config + " --target-depth 150 --speed 2 --speeds 1:2:1", "write no file" },
    { "tow_sim_chart" + config + " --cable-out 500 --depth-band 100:200 --no-plot", "write no file" },
    { "tow_sim_chart" + config + " --cable-out 500 --depth-band 100:200 --speed 2", "leave out --speed" },
    { "tow_sim_chart" + config + " --target-depth 150 --speed 2 --cable-out 500", "leave out --cable-out" },
    { "tow_sim_chart" + config + " --target-depth 150 --speed 2 --depth-band 100:200 --cable-out 5", "not both" },
    { "tow_sim_chart" + config + " --speeds 1:2:1 --cable-out 500 --out /tmp/x --speed 2", "--speeds FROM:TO:STEP" },
    { "tow_sim_chart" + config + " --target-depth 150 --speed 1:3:1", "--speed '1:3:1' must be one number" },
    { "tow_sim_response" + config + " --speed 1:3:1 --input heave --periods 5 --out /tmp/x",
      "--speed '1:3:1' must be one number" },
    { "tow_sim_response" + config + " --speed 2 --cable-out 300:500:100 --input heave --periods 5 --out /tmp/x",
      "--cable-out '300:500:100' must be one number" },
  };
  for (const auto& [command, why] : cases)
  {
    const size_t space = command.find(' ');
    const Outcome o = run(command.substr(0, space), command.substr(space + 1));
    EXPECT_EQ(o.status, 2) << command;
    EXPECT_NE(o.err.find(why), std::string::npos) << command << ": " << o.err;
  }
}

}  // namespace
