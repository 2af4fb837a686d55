#include "render/declared_markers.h"

#include <cmath>
#include <optional>

#include <Eigen/Geometry>

namespace pronk::render {
namespace {

constexpr int kArcPoints = 40;

// The named metrics' values, if every one was reported and is finite.
std::optional<std::vector<double>> valuesOf(const Trace& trace, const std::vector<std::string>& names) {
  std::vector<double> v;
  for (const std::string& n : names) {
    const double* x = trace.findMetric(n);
    if (!x || !std::isfinite(*x)) return std::nullopt;
    v.push_back(*x);
  }
  return v;
}

}  // namespace

void addDeclaredMarkers(SceneMarkers& markers, const Trace& trace, const EnvironmentSchema& schema,
                        const Terrain& terrain, const Eigen::Vector3d& gravity) {
  if (trace.samples.empty()) return;
  const TraceSample& s0 = trace.samples.front();
  const Eigen::Quaterniond q(s0.base_quaternion(0), s0.base_quaternion(1), s0.base_quaternion(2), s0.base_quaternion(3));
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const Eigen::AngleAxisd heading(std::atan2(R(1, 0), R(0, 0)), Eigen::Vector3d::UnitZ());
  const auto ground = terrain.topAt(s0.com_position.x(), s0.com_position.y());
  const double surface = ground ? ground->height : 0.0;
  const Eigen::Vector3d origin(s0.com_position.x(), s0.com_position.y(), surface);
  bool arc_done = false, point_done = false;
  for (const MarkerSpec& m : schema.markers) {
    const std::optional<std::vector<double>> v = valuesOf(trace, m.metrics);
    if (!v) continue;
    if (m.kind == MarkerSpec::Kind::Arc && !arc_done) {
      const Eigen::Vector3d p((*v)[0], (*v)[1], (*v)[2]), vel((*v)[3], (*v)[4], (*v)[5]);
      const double duration = (*v)[6];
      for (int i = 0; i <= kArcPoints; ++i) {
        const double t = duration * i / kArcPoints;
        markers.planned_arc.push_back(origin + heading * (p + vel * t) + 0.5 * gravity * t * t);
      }
      if (!m.label.empty()) markers.arc_label = m.label;
      arc_done = true;
    } else if (m.kind == MarkerSpec::Kind::Point && !point_done) {
      markers.predicted_landing = origin + heading * Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]);
      if (!m.label.empty()) markers.landing_label = m.label;
      point_done = true;
    }
  }
}

}  // namespace pronk::render
