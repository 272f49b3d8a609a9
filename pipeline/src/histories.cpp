#include "kinetofem/pipeline/histories.hpp"

#include <algorithm>
#include <cctype>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"

namespace kinetofem::pipeline {

namespace {

std::string clean(std::string name) {
  for (char& ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.')) ch = '_';
  return name;
}

bool is_angle(const mech::MultibodyModel& m, std::size_t drive) { return drive_effort_unit(m, drive) == "N*m"; }

void write_histories(post::ResultsWriter& w, const mech::MultibodyModel& m, const mech::Results& res) {
  const std::size_t T = res.frames.size();
  const std::vector<std::string> xy = {"x", "y"};
  auto column = [&](auto&& get, int cols) {
    post::FieldMatrix out(T, cols);
    for (std::size_t k = 0; k < T; ++k) get(res.frames[k], out.row(Eigen::Index(k)));
    return out;
  };
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const std::string p = "body." + m.bodies[b].name + ".";
    w.write_history(clean(p + post::layout::kPosition), "m", column([&](const mech::Frame& f, auto row) { row = f.bodies[b].q.head<2>().transpose(); }, 2), xy);
    w.write_history(clean(p + "angle"), "rad", column([&](const mech::Frame& f, auto row) { row(0) = f.bodies[b].q.z(); }, 1));
    w.write_history(clean(p + "velocity"), "m/s", column([&](const mech::Frame& f, auto row) { row = f.bodies[b].q_dot.head<2>().transpose(); }, 2), xy);
    w.write_history(clean(p + "angular_velocity"), "rad/s", column([&](const mech::Frame& f, auto row) { row(0) = f.bodies[b].q_dot.z(); }, 1));
    w.write_history(clean(p + "acceleration"), "m/s^2", column([&](const mech::Frame& f, auto row) { row = f.bodies[b].q_ddot.head<2>().transpose(); }, 2), xy);
    w.write_history(clean(p + "angular_acceleration"), "rad/s^2", column([&](const mech::Frame& f, auto row) { row(0) = f.bodies[b].q_ddot.z(); }, 1));
    w.write_history(clean(p + "com_position"), "m", column([&](const mech::Frame& f, auto row) { row = f.bodies[b].com.transpose(); }, 2), xy);
    w.write_history(clean(p + "com_acceleration"), "m/s^2", column([&](const mech::Frame& f, auto row) { row = f.bodies[b].com_acceleration.transpose(); }, 2), xy);
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    for (int side = 0; side < 2; ++side) {
      const std::string body = side == 0 ? m.joints[j].body_i : m.joints[j].body_j;
      const std::string p = "joint." + m.joints[j].name + ".on_" + body + ".";
      auto on = [side, j](const mech::Frame& f) -> const mech::Reaction& { return side == 0 ? f.joints[j].on_i : f.joints[j].on_j; };
      w.write_history(clean(p + "force_world"), "N", column([&](const mech::Frame& f, auto row) { row = on(f).force_world.transpose(); }, 2), xy);
      w.write_history(clean(p + "force_body"), "N", column([&](const mech::Frame& f, auto row) { row = on(f).force_body.transpose(); }, 2), xy);
      w.write_history(clean(p + "moment"), "N*m", column([&](const mech::Frame& f, auto row) { row(0) = on(f).moment_Nm; }, 1));
    }
  }
  const std::size_t n_drives = m.motion_drives.size() + m.force_drives.size();
  for (std::size_t d = 0; d < n_drives; ++d) {
    const std::string p = "drive." + res.frames.front().drives[d].name + ".";
    const bool angle = is_angle(m, d);
    w.write_history(clean(p + "s"), angle ? "rad" : "m", column([&](const mech::Frame& f, auto row) { row(0) = f.drives[d].s; }, 1));
    w.write_history(clean(p + "s_dot"), angle ? "rad/s" : "m/s", column([&](const mech::Frame& f, auto row) { row(0) = f.drives[d].s_dot; }, 1));
    w.write_history(clean(p + "s_ddot"), angle ? "rad/s^2" : "m/s^2", column([&](const mech::Frame& f, auto row) { row(0) = f.drives[d].s_ddot; }, 1));
    w.write_history(clean(p + "effort"), drive_effort_unit(m, d), column([&](const mech::Frame& f, auto row) { row(0) = f.drives[d].effort; }, 1));
    w.write_history(clean(p + "power"), "W", column([&](const mech::Frame& f, auto row) { row(0) = f.drives[d].power_W; }, 1));
  }
  for (std::size_t ch = 0; ch < res.frames.front().chains.size(); ++ch) {
    const std::string p = "chain." + res.frames.front().chains[ch].name + ".";
    w.write_history(clean(p + "tension"), "N", column([&](const mech::Frame& f, auto row) { row(0) = f.chains[ch].tension_N; }, 1));
    w.write_history(clean(p + "free_length"), "m", column([&](const mech::Frame& f, auto row) { row(0) = f.chains[ch].free_length_m; }, 1));
    w.write_history(clean(p + "wrap_angle"), "rad", column([&](const mech::Frame& f, auto row) { row(0) = f.chains[ch].wrap_angle_rad; }, 1));
  }
  for (std::size_t k = 0; k < res.frames.front().transmissions.size(); ++k) {
    const std::string p = "transmission." + res.frames.front().transmissions[k].name + ".";
    w.write_history(clean(p + "moment_output"), "N*m", column([&](const mech::Frame& f, auto row) { row(0) = f.transmissions[k].moment_output_Nm; }, 1));
    w.write_history(clean(p + "moment_input"), "N*m", column([&](const mech::Frame& f, auto row) { row(0) = f.transmissions[k].moment_input_Nm; }, 1));
    w.write_history(clean(p + "force"), "N", column([&](const mech::Frame& f, auto row) { row(0) = f.transmissions[k].force_N; }, 1));
  }
  w.write_history(clean("energy.kinetic"), "J", column([&](const mech::Frame& f, auto row) { row(0) = f.kinetic_energy_J; }, 1));
  w.write_history(clean("energy.potential"), "J", column([&](const mech::Frame& f, auto row) { row(0) = f.potential_energy_J; }, 1));
  w.write_history(clean("energy.work_drives"), "J", column([&](const mech::Frame& f, auto row) { row(0) = f.work_drives_J; }, 1));
  w.write_history(clean("energy.work_other"), "J", column([&](const mech::Frame& f, auto row) { row(0) = f.work_other_J; }, 1));
  w.write_history(clean("check.drift_position"), "m", column([&](const mech::Frame& f, auto row) { row(0) = f.drift_position_m; }, 1));
  w.write_history(clean("check.equilibrium_residual"), "1", column([&](const mech::Frame& f, auto row) { row(0) = f.equilibrium_residual; }, 1));
}


}  // namespace

std::string drive_effort_unit(const mech::MultibodyModel& m, std::size_t drive) {
  const std::size_t n_motion = m.motion_drives.size();
  const auto& rc = drive < n_motion ? m.motion_drives[drive].coordinate : m.force_drives[drive - n_motion].coordinate;
  return rc.type == mech::CoordinateType::Angle ? "N*m" : "N";
}


Eigen::Vector2d point_in_world(const mech::MultibodyModel& model, const mech::Frame& frame, const PathPoint& point) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].name != point.body) continue;
    Eigen::Vector2d local = Eigen::Vector2d::Zero();
    if (point.point != "origin") {
      const auto it = model.bodies[b].points.find(point.point);
      require(it != model.bodies[b].points.end(), "body '{}' has no point '{}'", point.body, point.point);
      local = it->second;
    }
    const Eigen::Vector3d q = frame.bodies.at(b).q;
    return q.head<2>() + Eigen::Rotation2Dd(q.z()) * local;
  }
  fail("no body '{}' to track point '{}' on", point.body, point.point);
}

void write_mechanism_histories(post::ResultsWriter& writer, const mech::MultibodyModel& model,
                               const mech::Results& results, const std::vector<PathPoint>& tracked) {
  require(!results.frames.empty(), "no output frames to write as histories");
  std::vector<double> times;
  for (const auto& f : results.frames) times.push_back(f.t);
  writer.set_mechanism_time(times);
  write_histories(writer, model, results);
  for (const auto& p : tracked) {
    post::FieldMatrix path(Eigen::Index(results.frames.size()), 2);
    for (std::size_t k = 0; k < results.frames.size(); ++k)
      path.row(Eigen::Index(k)) = point_in_world(model, results.frames[k], p).transpose();
    writer.write_history(clean("point." + p.body + "." + p.point), "m", path, {"x", "y"});
  }
}

}  // namespace kinetofem::pipeline
