// tow_sim_sweep (scripts/tow_sim_sweep) end to end: a 3 x 3 grid run on the local cores and on a real Dask
// distributed scheduler with two worker processes (loopback only, started here) gives the same summary;
// runs the batch refuses are reported with the key and the others complete; a sweep run again skips the
// runs it has and reruns one whose result was removed; a malformed sweep file is refused by name. Each
// summary row is checked against the run's own timeseries.csv (computed here).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const std::string kSweep = std::string(TOW_SIM_SOURCE_DIR) + "/scripts/tow_sim_sweep";
const std::string kBatch = TOW_SIM_BATCH_BINARY;

std::string run(const std::string& command, int* status)
{
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe)
    return "popen failed";
  std::array<char, 4096> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe))
    out += buffer.data();
  const int code = pclose(pipe);
  *status = WIFEXITED(code) ? WEXITSTATUS(code) : -1;
  return out;
}

std::string tempFolder()
{
  char name[] = "/tmp/tow_sim_sweep_test.XXXXXX";
  return mkdtemp(name) ? std::string(name) : std::string();
}

// One CSV line's cells (RFC 4180 quoting: "..." with "" for a quote).
std::vector<std::string> split(const std::string& line)
{
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      cells.back() += line[++i];
    else if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      cells.emplace_back();
    else
      cells.back() += c;
  }
  return cells;
}

// The rows of a CSV file as name -> value maps.
std::vector<std::map<std::string, std::string>> readCsv(const std::string& path)
{
  std::ifstream in(path);
  std::string line;
  std::vector<std::map<std::string, std::string>> rows;
  if (!std::getline(in, line))
    return rows;
  const std::vector<std::string> header = split(line);
  while (std::getline(in, line))
  {
    const std::vector<std::string> cells = split(line);
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < header.size(); ++c)
      row[header[c]] = c < cells.size() ? cells[c] : "";
    rows.push_back(row);
  }
  return rows;
}

// A summary without its wall times (which differ from run to run).
std::vector<std::map<std::string, std::string>> withoutWallTimes(std::vector<std::map<std::string, std::string>> rows)
{
  for (auto& row : rows)
    row.erase("wall_time_s");
  return rows;
}

// The number on the last non-empty line of a command's output.
int lastNumber(const std::string& out)
{
  const size_t end = out.find_last_not_of("\n ");
  if (end == std::string::npos)
    return 0;
  const size_t start = out.rfind('\n', end);
  return std::atoi(out.substr(start == std::string::npos ? 0 : start + 1).c_str());
}

double modified(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0 ? st.st_mtim.tv_sec + 1e-9 * st.st_mtim.tv_nsec : -1.0;
}

void writeSweep(const std::string& path)
{
  std::ofstream(path) << R"(scenario:
  cable: {length: 100.0, segments: 10}
  ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 100.0}]}
  simulation: {duration: 20.0, output_interval: 1.0, shape_interval: 100.0}
grid:
  cable.length: [80.0, 120.0, -5.0]
  ship.manoeuvres[0].speed: [1.0, 2.0, 2.5]
)";
}

// A free TCP port on the loopback (bind to 0, read it back).
int freePort()
{
  int status = 0;
  const std::string out =
      run("/usr/bin/python3 -c \"import socket; s = socket.socket(); s.bind(('127.0.0.1', 0)); "
          "print(s.getsockname()[1])\"",
          &status);
  return std::atoi(out.c_str());
}

// Starts a Dask scheduler on the loopback port and two single-threaded workers in `dir`, and waits (up to a
// minute) until both are registered; returns the last check's output.
std::string startDaskCluster(const std::string& dir, int port)
{
  const std::string address = "tcp://127.0.0.1:" + std::to_string(port);
  std::system(("cd " + dir + " && (setsid dask-scheduler --host 127.0.0.1 --port " + std::to_string(port) +
               " --no-dashboard > scheduler.log 2>&1 &)")
                  .c_str());
  for (int w = 0; w < 2; ++w)
    std::system(("cd " + dir + " && (setsid dask-worker " + address +
                 " --nworkers 1 --nthreads 1 --no-dashboard --no-nanny --host 127.0.0.1 > worker" + std::to_string(w) +
                 ".log 2>&1 &)")
                    .c_str());
  std::string check;
  int status = 0;
  for (int attempt = 0; attempt < 60; ++attempt)
  {
    check = run("/usr/bin/python3 -c \"from distributed import Client; c = Client('" + address +
                    "', timeout=5); print(len(c.scheduler_info()['workers']))\"",
                &status);
    if (status == 0 && lastNumber(check) >= 2)
      break;
    sleep(1);
  }
  return check;
}

TEST(Sweep, LocalAndDaskRunsGiveTheSameSummaryAndFailuresAreReported)
{
  const std::string dir = tempFolder();
  ASSERT_FALSE(dir.empty());
  writeSweep(dir + "/sweep.yaml");
  int status = 0;
  const std::string local =
      run(kSweep + " " + dir + "/sweep.yaml --out " + dir + "/local --jobs 2 --batch " + kBatch, &status);
  EXPECT_EQ(status, 1) << local;  // some runs refused
  EXPECT_NE(local.find("9 runs (9 run now, 0 already done): 6 ok, 3 refused"), std::string::npos) << local;
  const auto rows = readCsv(dir + "/local/summary.csv");
  ASSERT_EQ(rows.size(), 9u) << local;
  int ok = 0, refused = 0;
  for (const auto& row : rows)
  {
    if (row.at("cable.length") == "-5.0")
    {
      EXPECT_EQ(row.at("status"), "refused");
      EXPECT_NE(row.at("error").find("cable.length"), std::string::npos) << row.at("error");
      ++refused;
      continue;
    }
    EXPECT_EQ(row.at("status"), "ok") << row.at("error");
    ++ok;
    // The metrics are the run's own: the largest tension at the ship over its rows, by hand.
    const auto series =
        readCsv(dir + "/local/runs/" + std::string(4 - row.at("run").size(), '0') + row.at("run") + "/timeseries.csv");
    ASSERT_EQ(series.size(), 21u);
    double largest = 0.0, deepest = 0.0;
    for (const auto& r : series)
    {
      largest = std::max(largest, std::stod(r.at("tension_ship_max")));
      deepest = std::max(deepest, std::stod(r.at("depth")));
    }
    EXPECT_NEAR(std::stod(row.at("tension_ship_max")), largest, 1e-9 * largest);
    EXPECT_NEAR(std::stod(row.at("depth_max")), deepest, 1e-9 * deepest);
    EXPECT_EQ(row.at("t_reached"), "20");
  }
  EXPECT_EQ(ok, 6);
  EXPECT_EQ(refused, 3);
  // The slower tow hangs deeper (a sense check that the axis reached the runs).
  EXPECT_GT(std::stod(rows[0].at("depth_max")), std::stod(rows[1].at("depth_max")));

  // A Dask scheduler and two single-threaded worker processes on the loopback.
  const int port = freePort();
  ASSERT_GT(port, 0);
  const std::string address = "tcp://127.0.0.1:" + std::to_string(port);
  const std::string check = startDaskCluster(dir, port);
  const std::string dask = run(
      kSweep + " " + dir + "/sweep.yaml --out " + dir + "/dask --scheduler " + address + " --batch " + kBatch, &status);
  // ([d]: the pattern must not match the shell that runs pkill.)
  std::system(("pkill -f '[d]ask-worker " + address + "'").c_str());
  std::system(("pkill -f '[d]ask-scheduler --host 127.0.0.1 --port " + std::to_string(port) + " '").c_str());
  EXPECT_EQ(status, 1) << dask << check;
  EXPECT_EQ(withoutWallTimes(readCsv(dir + "/dask/summary.csv")), withoutWallTimes(rows)) << dask;
  // Both workers ran some.
  std::set<std::string> workers;
  for (int r = 0; r < 9; ++r)
  {
    std::ifstream in(dir + "/dask/runs/000" + std::to_string(r) + "/result.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = json.find("\"worker\": \"");
    if (at != std::string::npos)
      workers.insert(json.substr(at + 11, json.find('"', at + 11) - at - 11));
  }
  EXPECT_EQ(workers.size(), 2u) << dask;
  std::system(("rm -rf " + dir).c_str());
}

TEST(Sweep, ARunAgainSkipsFinishedRunsAndRerunsAMissingOne)
{
  const std::string dir = tempFolder();
  ASSERT_FALSE(dir.empty());
  writeSweep(dir + "/sweep.yaml");
  int status = 0;
  const std::string command = kSweep + " " + dir + "/sweep.yaml --out " + dir + "/out --batch " + kBatch;
  const std::string first = run(command, &status);
  const auto before = readCsv(dir + "/out/summary.csv");
  ASSERT_EQ(before.size(), 9u) << first;
  const double kept = modified(dir + "/out/runs/0000/result.json");
  std::remove((dir + "/out/runs/0004/result.json").c_str());
  const std::string again = run(command, &status);
  EXPECT_NE(again.find("9 runs (1 run now, 8 already done)"), std::string::npos) << again;
  EXPECT_EQ(modified(dir + "/out/runs/0000/result.json"), kept);
  EXPECT_GT(modified(dir + "/out/runs/0004/result.json"), 0.0);
  EXPECT_EQ(withoutWallTimes(readCsv(dir + "/out/summary.csv")), withoutWallTimes(before));
  // --retry-failed runs the three refused ones again.
  const std::string retry = run(command + " --retry-failed", &status);
  EXPECT_NE(retry.find("9 runs (3 run now, 6 already done)"), std::string::npos) << retry;
  std::system(("rm -rf " + dir).c_str());
}

// Random samples: the seed repeats them, each within its law, and each reached its run (the run's own
// resolved scenario.yaml holds the drawn value).
TEST(Sweep, RandomSamplesRepeatWithTheirSeedAndStayInTheirLaws)
{
  const std::string dir = tempFolder();
  ASSERT_FALSE(dir.empty());
  std::ofstream(dir + "/sweep.yaml") << R"(scenario:
  cable: {length: 100.0, segments: 10}
  ship: {manoeuvres: [{type: straight, speed: 2.0, duration: 100.0}]}
  simulation: {duration: 5.0, output_interval: 1.0, shape_interval: 100.0}
random:
  samples: 4
  seed: 7
  axes:
    cable.length: {uniform: [50.0, 150.0]}
    cable.segments: {choice: [5, 8]}
)";
  int status = 0;
  const std::string a = run(kSweep + " " + dir + "/sweep.yaml --out " + dir + "/a --batch " + kBatch, &status);
  EXPECT_EQ(status, 0) << a;
  const std::string b = run(kSweep + " " + dir + "/sweep.yaml --out " + dir + "/b --batch " + kBatch, &status);
  const auto rows = withoutWallTimes(readCsv(dir + "/a/summary.csv"));
  ASSERT_EQ(rows.size(), 4u) << a;
  EXPECT_EQ(withoutWallTimes(readCsv(dir + "/b/summary.csv")), rows) << b;
  std::set<std::string> lengths;
  for (const auto& row : rows)
  {
    const double length = std::stod(row.at("cable.length"));
    EXPECT_GE(length, 50.0);
    EXPECT_LE(length, 150.0);
    EXPECT_TRUE(row.at("cable.segments") == "5" || row.at("cable.segments") == "8") << row.at("cable.segments");
    lengths.insert(row.at("cable.length"));
    std::ifstream in(dir + "/a/runs/000" + row.at("run") + "/scenario.yaml");
    const std::string resolved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(resolved.find("segments: " + row.at("cable.segments")), std::string::npos) << resolved.substr(0, 300);
  }
  EXPECT_EQ(lengths.size(), 4u);  // four different draws
  std::system(("rm -rf " + dir).c_str());
}

TEST(Sweep, RefusesMalformedSweepFilesByName)
{
  const std::string dir = tempFolder();
  ASSERT_FALSE(dir.empty());
  const std::pair<const char*, const char*> cases[] = {
    { "scenario: {}\ngrid: {cable.length: [1.0]}\nrandm: {}\n", "unknown key 'randm'; did you mean 'random'?" },
    { "scenario: {}\nrandom: {samples: 2, sed: 1, axes: {cable.length: {uniform: [1, 2]}}}\n",
      "random: unknown key 'sed'; did you mean 'seed'?" },
    { "scenario: {}\nrandom: {samples: 2, cable.length: {uniform: [1, 2]}}\n",
      "random: unknown key 'cable.length' (known: axes, samples, seed)" },  // the axes belong one level down
    { "scenario: {}\n", "give one of 'grid'" },
    { "grid: {cable.length: [1.0]}\n", "give one of 'base'" },
    { "scenario: {}\ngrid: {cable..length: [1.0]}\n", "axis 'cable..length'" },
    { "scenario: {}\ngrid: {cable.length: []}\n", "grid.cable.length: a non-empty list" },
    { "scenario: {}\nrandom: {samples: 0, axes: {cable.length: {uniform: [1, 2]}}}\n", "random.samples = 0" },
    { "scenario: {}\nrandom: {samples: 2, axes: {cable.length: {normal: [1, 2]}}}\n", "random.axes.cable.length" },
    { "base: missing.yaml\ngrid: {cable.length: [1.0]}\n", "base 'missing.yaml' is not a readable file" },
  };
  for (const auto& [yaml, expected] : cases)
  {
    std::ofstream(dir + "/bad.yaml") << yaml;
    int status = 0;
    const std::string out = run(kSweep + " " + dir + "/bad.yaml --out " + dir + "/out --batch " + kBatch, &status);
    EXPECT_EQ(status, 2) << yaml << out;
    EXPECT_NE(out.find(expected), std::string::npos) << yaml << out;
  }
  std::system(("rm -rf " + dir).c_str());
}

}  // namespace
