#include "tow_sim/scenario/shape_replay.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "tow_sim/core/io/numeric_csv.h"

namespace tow_sim
{
namespace
{
// A run with cable sections writes an eighth column, `section` (docs/tools.md, "Output files").
bool hasSectionColumn(const std::string& path)
{
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#' && line.find_first_not_of(" \t\r") != std::string::npos)
      return line.find(",section") != std::string::npos;
  return false;
}
}  // namespace

std::vector<ShapeFrame> readShapes(const std::string& path)
{
  const bool sections = hasSectionColumn(path);
  const std::vector<NumericCsvRow> rows =
      readNumericCsv(path, sections ? 8 : 7, "shapes file",
                     sections ? "t, joint, x, y, z, tension, slack, section" : "t, joint, x, y, z, tension, slack");
  std::vector<ShapeFrame> frames;
  std::vector<Eigen::Vector3d> joints;
  auto close = [&]
  {
    if (frames.empty())
      return;
    ShapeFrame& f = frames.back();
    f.joints.resize(3, static_cast<Eigen::Index>(joints.size()));
    for (size_t j = 0; j < joints.size(); ++j)
      f.joints.col(static_cast<Eigen::Index>(j)) = joints[j];
    joints.clear();
  };
  for (const NumericCsvRow& r : rows)
  {
    const double t = r.values[0];
    if (frames.empty() || t != frames.back().t)
    {
      if (!frames.empty() && t < frames.back().t)
        throw std::invalid_argument("shapes file '" + path + "' line " + std::to_string(r.line) +
                                    ": t goes back in time");
      close();
      frames.emplace_back();
      frames.back().t = t;
    }
    if (r.values[1] != static_cast<double>(joints.size() + 1))
      throw std::invalid_argument("shapes file '" + path + "' line " + std::to_string(r.line) + ": joint " +
                                  std::to_string(static_cast<long>(r.values[1])) + " out of order (expected " +
                                  std::to_string(joints.size() + 1) + ")");
    joints.emplace_back(r.values[2], r.values[3], r.values[4]);
    frames.back().tension.push_back(r.values[5]);
    frames.back().slack.push_back(r.values[6] != 0.0);
  }
  close();
  if (frames.empty())
    throw std::invalid_argument("shapes file '" + path + "': no rows");
  return frames;
}

ShapeFrame shapeAt(const std::vector<ShapeFrame>& frames, double t)
{
  if (frames.empty())
    throw std::invalid_argument("shapeAt: no frames");
  if (t <= frames.front().t)
    return frames.front();
  if (t >= frames.back().t)
    return frames.back();
  const auto after =
      std::upper_bound(frames.begin(), frames.end(), t, [](double time, const ShapeFrame& f) { return time < f.t; });
  const ShapeFrame& b = *after;
  const ShapeFrame& a = *(after - 1);
  ShapeFrame out = a;
  out.t = t;
  if (a.joints.cols() != b.joints.cols())
    return out;
  const double w = (t - a.t) / (b.t - a.t);
  out.joints = (1.0 - w) * a.joints + w * b.joints;
  for (size_t j = 0; j < out.tension.size(); ++j)
    out.tension[j] = (1.0 - w) * a.tension[j] + w * b.tension[j];
  return out;
}

}  // namespace tow_sim
