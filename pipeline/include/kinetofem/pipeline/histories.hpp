#pragma once
// Stage "write the histories": the mechanism's results over the output times
// into the results file's /mechanism group (names and units: docs/results.md).
//
//   body.<b>.position, angle, velocity, angular_velocity, acceleration,
//       angular_acceleration, com_position, com_acceleration   (world frame)
//   joint.<j>.on_<b>.force_world, force_body, moment           (the joint's load on body b)
//   drive.<d>.s, s_dot, s_ddot, effort, power
//   chain.<c>.tension, free_length, wrap_angle
//   energy.kinetic, potential, work_drives, work_other; check.drift_position,
//       check.equilibrium_residual
//   point.<b>.<p>: the world path (x, y) of each tracked body point (e.g.
//       the gripper point H), m
// Names keep letters, digits, '_', '-' and '.'; any other character becomes '_'.
#include <string>
#include <vector>

#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::pipeline {

// A named point of a body ("origin" allowed) whose path is written as the
// histories point.<body>.<point>.* (position, velocity, acceleration).
struct PathPoint {
  std::string body, point;
};

void write_mechanism_histories(post::ResultsWriter& writer, const mech::MultibodyModel& model,
                               const mech::Results& results, const std::vector<PathPoint>& tracked = {});

// World position of a body point in a frame, m.
Eigen::Vector2d point_in_world(const mech::MultibodyModel& model, const mech::Frame& frame, const PathPoint& point);

// "N*m" for a drive on an angle, "N" on a displacement (drive index as in
// mech::Frame::drives: motion drives, then force drives).
std::string drive_effort_unit(const mech::MultibodyModel& model, std::size_t drive);

}  // namespace kinetofem::pipeline
