#include "tow_sim/ros/markers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tow_sim/core/constants.h"

#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
visualization_msgs::Marker baseMarker(const std_msgs::Header& header, const std::string& ns, int id, int type)
{
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color.a = 1.0;
  return m;
}

visualization_msgs::Marker tensionLine(const std_msgs::Header& header, const Eigen::Matrix3Xd& points,
                                       const std::vector<double>& tensions, const std::vector<bool>& slack,
                                       double width, double color_max)
{
  visualization_msgs::Marker cable = baseMarker(header, "cable", 0, visualization_msgs::Marker::LINE_STRIP);
  cable.scale.x = width;
  for (Eigen::Index j = 0; j < points.cols(); ++j)
  {
    const size_t i = static_cast<size_t>(j);
    cable.points.push_back(ros_conv::toPoint(points.col(j)));
    cable.colors.push_back(ros_conv::tensionColor(tensions[i], color_max, slack[i]));
  }
  return cable;
}

namespace
{

std_msgs::ColorRGBA rgba(double r, double g, double b, double a = 1.0)
{
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA grey(double level)
{
  return rgba(level, level, level);
}

// Cable: tow point to bail, each joint coloured by its tension (magenta where slack); with sections, a strip
// for each (ids 0 .. sections - 1: a section the winch or a parting left without segments is deleted).
void addCable(const TowSnapshot& s, const NodeParams& params, const CableLook& look, const std_msgs::Header& header,
              visualization_msgs::MarkerArray& array)
{
  std::vector<double> tensions(static_cast<size_t>(s.segments) + 1);
  for (int j = 0; j <= s.segments; ++j)
    tensions[static_cast<size_t>(j)] = s.tensions.col(j).norm();
  if (look.section_widths.size() <= 1)
  {
    array.markers.push_back(tensionLine(header, s.joints.leftCols(s.segments + 1), tensions, s.slack,
                                        params.cable_marker_width, params.tension_color_max));
    return;
  }
  for (size_t i = 0; i < look.section_widths.size(); ++i)
  {
    const auto first = std::find(s.segment_section.begin(), s.segment_section.end(), static_cast<int>(i));
    const auto last = std::find_if(first, s.segment_section.end(), [&](int k) { return k != static_cast<int>(i); });
    const Eigen::Index from = first - s.segment_section.begin(), count = last - first;
    visualization_msgs::Marker m =
        tensionLine(header, s.joints.middleCols(from, count > 0 ? count + 1 : 0),
                    std::vector<double>(tensions.begin() + from, tensions.begin() + from + (count > 0 ? count + 1 : 0)),
                    std::vector<bool>(s.slack.begin() + from, s.slack.begin() + from + (count > 0 ? count + 1 : 0)),
                    look.section_widths[i], params.tension_color_max);
    m.id = static_cast<int>(i);
    if (count == 0)
      m.action = visualization_msgs::Marker::DELETE;
    array.markers.push_back(m);
  }
}

// Point bodies: spheres at their joints (deleted once a parting took one off the vehicle side).
void addBodies(const TowSnapshot& s, const CableLook& look, const std_msgs::Header& header,
               visualization_msgs::MarkerArray& array)
{
  for (size_t i = 0; i < s.bodies.size() && i < look.body_diameters.size(); ++i)
  {
    visualization_msgs::Marker m =
        baseMarker(header, "cable_bodies", static_cast<int>(i), visualization_msgs::Marker::SPHERE);
    const BodyOutput& b = s.bodies[i];
    if (b.joint < 0)
      m.action = visualization_msgs::Marker::DELETE;
    else
      m.pose.position = ros_conv::toPoint(b.p_W);
    m.scale.x = m.scale.y = m.scale.z = look.body_diameters[i];
    m.color = grey(0.25);  // a clump
    if (look.body_floats[i])
    {
      m.color = rgba(1.0, 0.85, 0.0);  // a float: yellow
    }
    array.markers.push_back(m);
  }
}

// After a parting aft of the tow point, the cable left on the ship ("cable_ship_side"; deleted when none).
visualization_msgs::Marker shipSideMarker(const TowSnapshot& s, const NodeParams& params,
                                          const std_msgs::Header& header)
{
  const Eigen::Index n = s.ship_side.cols();
  std::vector<double> tensions(static_cast<size_t>(n), 0.0);  // the last joint is free
  for (Eigen::Index j = 0; j + 1 < n; ++j)
    tensions[static_cast<size_t>(j)] = s.ship_side_tensions.col(j).norm();
  visualization_msgs::Marker m = tensionLine(header, s.ship_side, tensions, std::vector<bool>(tensions.size(), false),
                                             params.cable_marker_width, params.tension_color_max);
  m.ns = "cable_ship_side";
  if (n == 0)
    m.action = visualization_msgs::Marker::DELETE;
  return m;
}

// Hull (an orange ellipsoid from the nose to the tail point) and four fins at their actual deflections, drawn
// vehicle_marker_scale times their size about the hull's centre (half transparent when enlarged).
void addVehicle(const TowSnapshot& s, const VehicleParams& vp, const NodeParams& params, const std_msgs::Header& header,
                visualization_msgs::MarkerArray& array)
{
  using visualization_msgs::Marker;
  const double k = params.vehicle_marker_scale, alpha = k > 1.0 ? 0.5 : 1.0;
  const Eigen::Vector3d bail = s.joints.col(s.segments), tail = s.joints.col(s.segments + 1);
  const Eigen::Vector3d centre =
      bail + 0.5 * (vp.tail_from_bail - vp.nose_from_bail) / vp.tail_from_bail * (tail - bail);
  auto pointAt = [&](double from_bail) -> Eigen::Vector3d
  { return centre + k * (bail + from_bail / vp.tail_from_bail * (tail - bail) - centre); };
  const double hull_length = vp.nose_from_bail + vp.tail_from_bail, diameter = k * params.vehicle_diameter;
  Marker hull = baseMarker(header, "vehicle", 0, Marker::SPHERE);
  hull.pose.position = ros_conv::toPoint(centre);
  hull.pose.orientation = ros_conv::toQuaternion(s.attitude);
  hull.scale.x = k * hull_length;
  hull.scale.y = hull.scale.z = diameter;
  hull.color = rgba(1.0, 0.5, 0.0, alpha);  // orange: apart from the cable's colour scale below 3/4 of it
  array.markers.push_back(hull);

  const double span = 0.8 * diameter, chord = 0.12 * k * hull_length;
  const Eigen::Matrix3d R = s.attitude.toRotationMatrix();
  auto fin = [&](int id, double from_bail, const Eigen::Vector3d& side_B, const Eigen::Quaterniond& deflection,
                 const Eigen::Vector3d& size)
  {
    Marker m = baseMarker(header, "vehicle", id, Marker::CUBE);
    m.pose.position = ros_conv::toPoint(pointAt(from_bail) + R * ((0.5 * diameter + 0.5 * span) * side_B));
    m.pose.orientation = ros_conv::toQuaternion(s.attitude * deflection);
    m.scale.x = size.x();
    m.scale.y = size.y();
    m.scale.z = size.z();
    m.color = grey(0.35);
    m.color.a = alpha;
    array.markers.push_back(m);
  };
  // Positive rudder turns the leading edge to port (about +z_b); positive elevator lifts it (about -y_b).
  const Eigen::Quaterniond rudder(Eigen::AngleAxisd(s.vehicle.rudder, Eigen::Vector3d::UnitZ()));
  // The elevator's differential (physics.md (P57a)): starboard fin at elevator + differential, port at minus.
  const double e = s.vehicle.elevator, d = s.vehicle.differential;
  const Eigen::Quaterniond port(Eigen::AngleAxisd(-(e - d), Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond starboard(Eigen::AngleAxisd(-(e + d), Eigen::Vector3d::UnitY()));
  const double thickness = 0.02 * k;
  fin(1, vp.vertical_fin_from_bail, Eigen::Vector3d::UnitZ(), rudder, Eigen::Vector3d(chord, thickness, span));
  fin(2, vp.vertical_fin_from_bail, -Eigen::Vector3d::UnitZ(), rudder, Eigen::Vector3d(chord, thickness, span));
  fin(3, vp.horizontal_fin_from_bail, Eigen::Vector3d::UnitY(), port, Eigen::Vector3d(chord, span, thickness));
  fin(4, vp.horizontal_fin_from_bail, -Eigen::Vector3d::UnitY(), starboard, Eigen::Vector3d(chord, span, thickness));
}

// The cable's pull on the ship, -T_1, drawn from the tow point, and the tension labels.
void addForceAndLabels(const TowSnapshot& s, const NodeParams& params, const std_msgs::Header& header,
                       visualization_msgs::MarkerArray& array)
{
  using visualization_msgs::Marker;
  Marker arrow = baseMarker(header, "tow_force", 0, Marker::ARROW);
  const Eigen::Vector3d tow_point = s.tow_point.p_W;  // the ship's, also after a parting
  arrow.points.push_back(ros_conv::toPoint(tow_point));
  arrow.points.push_back(ros_conv::toPoint(tow_point - params.force_arrow_scale * shipPull(s)));
  arrow.scale.x = 0.4;
  arrow.scale.y = 0.8;
  arrow.scale.z = 1.0;
  arrow.color = rgba(1.0, 0.2, 0.2);
  array.markers.push_back(arrow);

  char text[128];
  const double h = params.label_height, k = params.vehicle_marker_scale;
  Marker ship_label = baseMarker(header, "labels", 0, Marker::TEXT_VIEW_FACING);
  std::snprintf(text, sizeof(text), "T ship %.0f N", s.tension_ship);
  ship_label.text = text;
  ship_label.pose.position = ros_conv::toPoint(tow_point + Eigen::Vector3d(0.0, 0.0, 3.0 + 1.5 * h));
  ship_label.scale.z = h;
  ship_label.color = grey(1.0);
  array.markers.push_back(ship_label);
  Marker vehicle_label = baseMarker(header, "labels", 1, Marker::TEXT_VIEW_FACING);
  if (k > 1.0)
    std::snprintf(text, sizeof(text), "T vehicle %.0f N, depth %.1f m (drawn x%g)", s.tension_vehicle, s.depth, k);
  else
    std::snprintf(text, sizeof(text), "T vehicle %.0f N, depth %.1f m", s.tension_vehicle, s.depth);
  vehicle_label.text = text;
  vehicle_label.pose.position =
      ros_conv::toPoint(s.vehicle.p_cg_W + Eigen::Vector3d(0.0, 0.0, k * params.vehicle_diameter + 0.75 * h));
  vehicle_label.scale.z = 0.5 * h;
  vehicle_label.color = grey(1.0);
  array.markers.push_back(vehicle_label);
}

// The seabed around a point: an 800 m square of grid lines 40 m apart, on the bottom (lines are unlit, so
// they read at any viewing angle, like the sea surface grid).
visualization_msgs::Marker seabedMarker(const Seabed& seabed, const Eigen::Vector3d& centre_W,
                                        const std_msgs::Header& header)
{
  visualization_msgs::Marker bottom = baseMarker(header, "seabed", 0, visualization_msgs::Marker::LINE_LIST);
  bottom.scale.x = 0.6;
  bottom.color = rgba(0.85, 0.75, 0.5);  // sand
  const double step = 40.0, half = 400.0;
  const double x0 = std::round(centre_W.x() / step) * step - half, y0 = std::round(centre_W.y() / step) * step - half;
  auto at = [&](double x, double y) { return ros_conv::toPoint(Eigen::Vector3d(x, y, seabed.bottomZ(x, y))); };
  for (double a = 0.0; a <= 2 * half + 1e-9; a += step)
    for (double b = 0.0; b < 2 * half - 1e-9; b += step)
    {
      bottom.points.push_back(at(x0 + a, y0 + b));  // along y
      bottom.points.push_back(at(x0 + a, y0 + b + step));
      bottom.points.push_back(at(x0 + b, y0 + a));  // along x
      bottom.points.push_back(at(x0 + b + step, y0 + a));
    }
  return bottom;
}
// The ship as a hull outline at its reference point and heading, on the surface (ns "ship", id 0), its
// body above the water (id 2) and its tow point (id 1).
void addShip(const TowSnapshot& s, const NodeParams& params, const std_msgs::Header& header,
             visualization_msgs::MarkerArray& array)
{
  using visualization_msgs::Marker;
  Marker hull = baseMarker(header, "ship", 0, Marker::LINE_STRIP);
  hull.scale.x = 0.8;
  hull.color = grey(0.9);
  const double l = 0.5 * params.ship_length, b = 0.5 * params.ship_beam;
  // Stern corners, the parallel body to 60 % of the length, a pointed bow (ship frame, FLU).
  const double outline[][2] = { { -l, -b }, { 0.2 * l, -b }, { l, 0.0 }, { 0.2 * l, b }, { -l, b }, { -l, -b } };
  const double c = std::cos(s.ship.heading), sn = std::sin(s.ship.heading);
  for (const auto& xy : outline)
    hull.points.push_back(
        ros_conv::toPoint(Eigen::Vector3d(s.ship.x + c * xy[0] - sn * xy[1], s.ship.y + sn * xy[0] + c * xy[1], 0.0)));
  array.markers.push_back(hull);
  // Its body above the waterline, a cream box to 5 m of freeboard over the parallel body and bow (id 2):
  // lit from the side it reads at any view, where the outline alone is a thin line.
  Marker body = baseMarker(header, "ship", 2, Marker::CUBE);
  body.pose.position =
      ros_conv::toPoint(Eigen::Vector3d(s.ship.x - 0.1 * l * c, s.ship.y - 0.1 * l * sn, 2.5));  // x from -l to 0.8 l
  body.pose.orientation =
      ros_conv::toQuaternion(Eigen::Quaterniond(Eigen::AngleAxisd(s.ship.heading, Eigen::Vector3d::UnitZ())));
  body.scale.x = 1.8 * l;
  body.scale.y = 2.0 * b;
  body.scale.z = 5.0;
  body.color = rgba(0.95, 0.9, 0.72);
  array.markers.push_back(body);
  Marker tow_point = baseMarker(header, "ship", 1, Marker::SPHERE);
  tow_point.pose.position = ros_conv::toPoint(s.tow_point.p_W);
  tow_point.scale.x = tow_point.scale.y = tow_point.scale.z = 2.0;
  tow_point.color = rgba(1.0, 0.8, 0.1);
  array.markers.push_back(tow_point);
}

// A trail as a line strip through its samples to the current position (ns "trails").
visualization_msgs::Marker trailMarker(const TrackTrail& trail, const Eigen::Vector3d& now, int id,
                                       const std_msgs::ColorRGBA& color, const std_msgs::Header& header)
{
  visualization_msgs::Marker line = baseMarker(header, "trails", id, visualization_msgs::Marker::LINE_STRIP);
  line.scale.x = 0.5;
  line.color = color;
  for (const TrackTrail::Sample& sample : trail.samples())
    line.points.push_back(ros_conv::toPoint(sample.p));
  line.points.push_back(ros_conv::toPoint(now));
  return line;
}
}  // namespace

CableLook cableLook(const SimulationConfig& config, double width)
{
  CableLook look;
  for (const CableParams& section : config.sections)
    look.section_widths.push_back(width * std::clamp(section.diameter / config.sections.front().diameter, 0.25, 4.0));
  const double rho = config.environment.water_density;
  for (const CableBodyParams& b : config.bodies)
  {
    look.body_diameters.push_back(std::max(3.0 * width, std::cbrt(6.0 * b.body.displaced_volume / kPi)));
    look.body_floats.push_back(rho * b.body.displaced_volume > b.body.mass);
  }
  return look;
}

visualization_msgs::MarkerArray makeMarkers(const TowSnapshot& s, const VehicleParams& vehicle, const Seabed* seabed,
                                            const NodeParams& params, const std_msgs::Header& header,
                                            const MarkerTrails& trails, const CableLook& look)
{
  visualization_msgs::MarkerArray array;
  addCable(s, params, look, header, array);
  addBodies(s, look, header, array);
  array.markers.push_back(shipSideMarker(s, params, header));
  addVehicle(s, vehicle, params, header, array);
  addForceAndLabels(s, params, header, array);
  addShip(s, params, header, array);
  if (trails.ship)
    array.markers.push_back(trailMarker(*trails.ship, Eigen::Vector3d(s.ship.x, s.ship.y, 0.0), 0, grey(0.6), header));
  if (trails.vehicle)
  {
    // Pink: apart from the vehicle's orange and the cable's colour scale.
    array.markers.push_back(trailMarker(*trails.vehicle, s.vehicle.p_cg_W, 1, rgba(1.0, 0.7, 0.75), header));
  }
  if (seabed)
    array.markers.push_back(seabedMarker(*seabed, s.vehicle.p_cg_W, header));
  return array;
}

}  // namespace tow_sim
