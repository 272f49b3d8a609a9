// The printed summary of a run (pipeline/run_report.hpp): the extremes of the
// mechanism's efforts and chain tensions, the parts' extremes and table.
// Frames are written by hand here, so every expected value is a hand scan of
// the numbers below.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "kinetofem/pipeline/run_report.hpp"

namespace kinetofem::pipeline {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A model with one revolute joint "J", a motion drive "turn" (angle) and a
// force drive "push" (displacement), and frames at t = 0, 0.1, 0.2, 0.3 with
// the efforts and tensions given (chains "c1", "c2").
struct HandMade {
  mech::MultibodyModel model;
  mech::Results results;
};

HandMade hand_made(const std::vector<double>& turn, const std::vector<double>& push,
                   const std::vector<std::vector<double>>& tensions) {
  HandMade h;
  h.model.bodies.resize(2);
  h.model.bodies[0].name = "ground";
  h.model.bodies[1].name = "link";
  h.model.joints.push_back(mech::make_revolute("J", "ground", "origin", "link", "origin"));
  mech::MotionDrive turn_drive;
  turn_drive.name = "turn";
  turn_drive.coordinate.type = mech::CoordinateType::Angle;
  h.model.motion_drives.push_back(turn_drive);
  mech::ForceDrive push_drive;
  push_drive.name = "push";
  push_drive.coordinate.type = mech::CoordinateType::Displacement;
  h.model.force_drives.push_back(push_drive);
  for (std::size_t k = 0; k < turn.size(); ++k) {
    mech::Frame f;
    f.t = 0.1 * double(k);
    mech::DriveFrame a, b;
    a.name = "turn";
    a.prescribed = true;
    a.effort = turn[k];
    b.name = "push";
    b.effort = push[k];
    f.drives = {a, b};
    mech::JointFrame j;
    j.name = "J";
    j.on_j.force_world = {3.0 * double(k), 4.0 * double(k)};  // |F| = 5 k N
    j.on_i.force_world = -j.on_j.force_world;
    f.joints = {j};
    for (std::size_t c = 0; c < tensions.size(); ++c) {
      mech::ChainFrame chain;
      chain.name = "c" + std::to_string(c + 1);
      chain.tension_N = tensions[c][k];
      f.chains.push_back(chain);
    }
    h.results.frames.push_back(f);
  }
  return h;
}

TEST(MechanismExtremes, ExtremesAreTheHandScanOfTheFrames) {
  // turn: 1, -7, 3, 2 N m; push: 0.5, 4, -2, 6 N -> max |effort| 7.
  // c1: 10, 5, 8, 12 N; c2: 3, -1, 20, 4 N -> min -1 N, max 20 N (over both).
  const HandMade h = hand_made({1, -7, 3, 2}, {0.5, 4, -2, 6}, {{10, 5, 8, 12}, {3, -1, 20, 4}});
  const MechanismExtremes e = mechanism_extremes(h.model, h.results);
  EXPECT_EQ(e.max_abs_drive_effort, 7.0);
  EXPECT_EQ(e.min_chain_tension_n, -1.0);
  EXPECT_EQ(e.max_chain_tension_n, 20.0);
}

TEST(MechanismExtremes, FirstChainDoesNotHideTheOthers) {
  // The extremes of the first chain lie inside those of the second: min 2,
  // max 30 come from c2 alone.
  const HandMade h = hand_made({0, 0, 0, 0}, {0, 0, 0, 0}, {{10, 5, 8, 12}, {3, 2, 30, 4}});
  const MechanismExtremes e = mechanism_extremes(h.model, h.results);
  EXPECT_EQ(e.min_chain_tension_n, 2.0);
  EXPECT_EQ(e.max_chain_tension_n, 30.0);
}

TEST(MechanismExtremes, TextNamesEveryDriveJointAndChainWithUnits) {
  const HandMade h = hand_made({1, -7, 3, 2}, {0.5, 4, -2, 6}, {{10, 5, 8, 12}, {3, -1, 20, 4}});
  const std::string text = mechanism_extremes(h.model, h.results).text;
  // turn: min -7 N*m at t = 0.1 s, max 3 N*m at 0.2 s; push: -2 N at 0.2 s .. 6 N at 0.3 s.
  EXPECT_TRUE(contains(text, "(motion): effort -7 N*m (t = 0.1 s) .. 3 N*m (t = 0.2 s)")) << text;
  EXPECT_TRUE(contains(text, "(force) : effort -2 N (t = 0.2 s) .. 6 N (t = 0.3 s)")) << text;
  EXPECT_TRUE(contains(text, "max |reaction| 15 N (t = 0.3 s)")) << text;  // |(9, 12)|
  // c1 never slack; c2 pushes (-1 N) at t = 0.1 s.
  std::istringstream lines(text);
  std::string line;
  int chains = 0;
  while (std::getline(lines, line)) {
    if (contains(line, "chain c1")) {
      ++chains;
      EXPECT_FALSE(contains(line, "SLACK")) << line;
    }
    if (contains(line, "chain c2")) {
      ++chains;
      EXPECT_TRUE(contains(line, "-1 N (min, t = 0.1 s) .. 20 N  SLACK")) << line;
    }
  }
  EXPECT_EQ(chains, 2) << text;
}

TEST(MechanismExtremes, NoChainOrNoFramesGiveZeros) {
  const HandMade h = hand_made({1, -7}, {0.5, 4}, {});
  const MechanismExtremes e = mechanism_extremes(h.model, h.results);
  EXPECT_EQ(e.min_chain_tension_n, 0.0);
  EXPECT_EQ(e.max_chain_tension_n, 0.0);
  const MechanismExtremes none = mechanism_extremes(h.model, mech::Results{});
  EXPECT_EQ(none.max_abs_drive_effort, 0.0);
  EXPECT_TRUE(none.text.empty());
}

PartSummary summary(const std::string& body, double vm, double u, double static_vm, double static_u) {
  PartSummary p;
  p.body = body;
  p.dofs = 3000;
  p.peak_von_mises_pa = vm;
  p.peak_von_mises_time_s = 0.25;
  p.peak_displacement_m = u;
  p.peak_displacement_time_s = 0.5;
  p.static_von_mises_pa = static_vm;
  p.static_displacement_m = static_u;
  p.solver_summary = "CHOLMOD (" + body + ")";
  return p;
}

TEST(PartExtremes, MaximaOverThePartsEachOnItsOwn) {
  // Each maximum may come from a different part.
  const PartExtremes e =
      part_extremes({summary("lever", 80e6, 1e-4, 5e6, 3e-5), summary("arm", 60e6, 2e-4, 9e6, 1e-5)});
  EXPECT_EQ(e.max_von_mises_pa, 80e6);
  EXPECT_EQ(e.max_displacement_m, 2e-4);
  EXPECT_EQ(e.static_max_von_mises_pa, 9e6);
  EXPECT_EQ(e.static_max_displacement_m, 3e-5);
}

TEST(FormatPartTable, ListsEveryPartInMpaAndMm) {
  const std::string table =
      format_part_table({summary("lever", 80.5e6, 1.25e-4, 5e6, 3e-5), summary("arm", 60.25e6, 2e-4, 9e6, 1e-5)});
  // 80.5e6 Pa = 80.500 MPa, 1.25e-4 m = 0.12500 mm (the table's units).
  EXPECT_TRUE(contains(table, "80.500")) << table;
  EXPECT_TRUE(contains(table, "0.12500")) << table;
  EXPECT_TRUE(contains(table, "60.250")) << table;
  for (const char* body : {"lever", "arm"}) {
    EXPECT_TRUE(contains(table, std::string("  ") + body + " ")) << body << "\n" << table;
    EXPECT_TRUE(contains(table, std::string("solver: CHOLMOD (") + body + ")")) << body << "\n" << table;
  }
  // Header + one row per part + one solver line per part.
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 5) << table;
  // Parts in several planes: one more line, saying whose stress has the moments between the planes.
  const std::string planes = format_part_table({summary("lever", 80.5e6, 1.25e-4, 5e6, 3e-5)}, true);
  EXPECT_TRUE(contains(planes, "the parts sit in several planes")) << planes;
  EXPECT_TRUE(contains(planes, "elastic assembly's stress")) << planes;
}

}  // namespace
}  // namespace kinetofem::pipeline
