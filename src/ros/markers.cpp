#include "tow_sim/ros/markers.h"

#include <cmath>
#include <cstdio>

#include "tow_sim/ros/conversions.h"

namespace tow_sim
{
namespace
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

std_msgs::ColorRGBA grey(double level)
{
  std_msgs::ColorRGBA c;
  c.r = c.g = c.b = level;
  c.a = 1.0;
  return c;
}
}  // namespace

visualization_msgs::MarkerArray makeMarkers(const Simulator& sim, const Vehicle& vehicle, const VehicleOutputs& out,
                                            const Eigen::Quaterniond& q_published, const NodeParams& params,
                                            const std_msgs::Header& header)
{
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray array;
  const Eigen::Matrix3Xd joints = sim.jointPositions();
  const Eigen::Matrix3Xd& tensions = sim.tensions();
  const int nu = sim.geometry().segments;

  // Cable: tow point to bail, each joint coloured by its tension.
  Marker cable = baseMarker(header, "cable", 0, Marker::LINE_STRIP);
  cable.scale.x = params.cable_marker_width;
  for (int j = 0; j <= nu; ++j)
  {
    cable.points.push_back(ros_conv::toPoint(joints.col(j)));
    const Eigen::Vector3d s = (joints.col(j + 1) - joints.col(j)).normalized();
    const bool slack = tensions.col(j).dot(s) > 0.0;
    cable.colors.push_back(ros_conv::tensionColor(tensions.col(j).norm(), params.tension_color_max, slack));
  }
  array.markers.push_back(cable);

  // Hull: an ellipsoid from the nose to the tail point.
  const VehicleParams& vp = vehicle.params();
  const ElementKinematics k = sim.elementKinematics(nu);
  const double hull_length = vp.nose_from_bail + vp.tail_from_bail;
  Marker hull = baseMarker(header, "vehicle", 0, Marker::SPHERE);
  hull.pose.position = ros_conv::toPoint(k.pointAt(0.5 * (vp.tail_from_bail - vp.nose_from_bail) / vp.tail_from_bail));
  hull.pose.orientation = ros_conv::toQuaternion(q_published);
  hull.scale.x = hull_length;
  hull.scale.y = hull.scale.z = params.vehicle_diameter;
  hull.color = grey(0.85);
  array.markers.push_back(hull);

  // Fins: thin plates beside the hull at their actual deflections.
  const double span = 0.8 * params.vehicle_diameter, chord = 0.12 * hull_length;
  const Eigen::Matrix3d R = q_published.toRotationMatrix();
  auto fin = [&](int id, double from_bail, const Eigen::Vector3d& side_B, const Eigen::Quaterniond& deflection,
                 const Eigen::Vector3d& size)
  {
    Marker m = baseMarker(header, "vehicle", id, Marker::CUBE);
    const Eigen::Vector3d root = k.pointAt(from_bail / vp.tail_from_bail);
    m.pose.position = ros_conv::toPoint(root + R * ((0.5 * params.vehicle_diameter + 0.5 * span) * side_B));
    m.pose.orientation = ros_conv::toQuaternion(q_published * deflection);
    m.scale.x = size.x();
    m.scale.y = size.y();
    m.scale.z = size.z();
    m.color.r = 1.0;
    m.color.g = 0.55;
    array.markers.push_back(m);
  };
  // Positive rudder turns the leading edge to port (about +z_b); positive elevator lifts it (about -y_b).
  const Eigen::Quaterniond rudder(Eigen::AngleAxisd(out.rudder, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond elevator(Eigen::AngleAxisd(-out.elevator, Eigen::Vector3d::UnitY()));
  fin(1, vp.vertical_fin_from_bail, Eigen::Vector3d::UnitZ(), rudder, Eigen::Vector3d(chord, 0.02, span));
  fin(2, vp.vertical_fin_from_bail, -Eigen::Vector3d::UnitZ(), rudder, Eigen::Vector3d(chord, 0.02, span));
  fin(3, vp.horizontal_fin_from_bail, Eigen::Vector3d::UnitY(), elevator, Eigen::Vector3d(chord, span, 0.02));
  fin(4, vp.horizontal_fin_from_bail, -Eigen::Vector3d::UnitY(), elevator, Eigen::Vector3d(chord, span, 0.02));

  // The cable's pull on the ship, -T_1, drawn from the tow point.
  Marker arrow = baseMarker(header, "tow_force", 0, Marker::ARROW);
  const Eigen::Vector3d tow_point = joints.col(0);
  arrow.points.push_back(ros_conv::toPoint(tow_point));
  arrow.points.push_back(ros_conv::toPoint(tow_point - params.force_arrow_scale * tensions.col(0)));
  arrow.scale.x = 0.4;
  arrow.scale.y = 0.8;
  arrow.scale.z = 1.0;
  arrow.color.r = 1.0;
  arrow.color.g = 0.2;
  arrow.color.b = 0.2;
  array.markers.push_back(arrow);

  // Labels.
  char text[96];
  Marker ship_label = baseMarker(header, "labels", 0, Marker::TEXT_VIEW_FACING);
  std::snprintf(text, sizeof(text), "T ship %.0f N", tensions.col(0).norm());
  ship_label.text = text;
  ship_label.pose.position = ros_conv::toPoint(tow_point + Eigen::Vector3d(0.0, 0.0, 6.0));
  ship_label.scale.z = 3.0;
  ship_label.color = grey(1.0);
  array.markers.push_back(ship_label);
  Marker vehicle_label = baseMarker(header, "labels", 1, Marker::TEXT_VIEW_FACING);
  std::snprintf(text, sizeof(text), "T vehicle %.0f N, depth %.1f m", tensions.col(nu).norm(), out.depth);
  vehicle_label.text = text;
  vehicle_label.pose.position = ros_conv::toPoint(out.p_cg_W + Eigen::Vector3d(0.0, 0.0, 3.0));
  vehicle_label.scale.z = 1.5;
  vehicle_label.color = grey(1.0);
  array.markers.push_back(vehicle_label);

  // The seabed around the vehicle: an 800 m square of grid lines 40 m apart, on the bottom (lines are
  // unlit, so they read at any viewing angle, like the sea surface grid).
  const Seabed* seabed = sim.model().seabed();
  if (seabed)
  {
    Marker bottom = baseMarker(header, "seabed", 0, Marker::LINE_LIST);
    bottom.scale.x = 0.6;
    bottom.color.r = 0.85;  // sand
    bottom.color.g = 0.75;
    bottom.color.b = 0.5;
    bottom.color.a = 1.0;
    const double step = 40.0, half = 400.0;
    const double x0 = std::round(out.p_cg_W.x() / step) * step - half,
                 y0 = std::round(out.p_cg_W.y() / step) * step - half;
    auto at = [&](double x, double y) { return ros_conv::toPoint(Eigen::Vector3d(x, y, seabed->bottomZ(x, y))); };
    for (double a = 0.0; a <= 2 * half + 1e-9; a += step)
      for (double b = 0.0; b < 2 * half - 1e-9; b += step)
      {
        bottom.points.push_back(at(x0 + a, y0 + b));  // along y
        bottom.points.push_back(at(x0 + a, y0 + b + step));
        bottom.points.push_back(at(x0 + b, y0 + a));  // along x
        bottom.points.push_back(at(x0 + b + step, y0 + a));
      }
    array.markers.push_back(bottom);
  }
  return array;
}

}  // namespace tow_sim
