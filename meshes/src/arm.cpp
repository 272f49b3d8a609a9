#include "kinetofem/meshes/arm.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geometry_text.hpp"

namespace kinetofem::meshes {

namespace {

// Area of the disc of radius rho within the strip |y| <= a.
double disc_strip_area(double rho, double a) {
  if (a >= rho) return std::numbers::pi * rho * rho;
  return 2 * (a * std::sqrt(rho * rho - a * a) + rho * rho * std::asin(a / rho));
}

}  // namespace

void ArmDimensions::validate() const {
  for (const auto& [name, value] :
       {std::pair{"length_m", length_m}, {"gripper_offset_m", gripper_offset_m},
        {"arm_depth_m", arm_depth_m}, {"arm_thickness_m", arm_thickness_m},
        {"bore_diameter_m", bore_diameter_m}, {"boss_diameter_m", boss_diameter_m},
        {"boss_length_m", boss_length_m}, {"bracket_width_m", bracket_width_m},
        {"bracket_thickness_m", bracket_thickness_m}, {"mount_length_m", mount_length_m},
        {"mount_width_m", mount_width_m}, {"mount_thickness_m", mount_thickness_m}})
    require(std::isfinite(value) && value > 0, "arm dimension {} = {} must be positive", name,
            value);
  if (with_roller) {
    for (const auto& [name, value] : {std::pair{"roller_radius_m", roller_radius_m},
                                      {"roller_thickness_m", roller_thickness_m}})
      require(std::isfinite(value) && value > 0, "arm dimension {} = {} must be positive", name,
              value);
  } else {
    require(std::isfinite(bore_b_offset_m) && bore_b_offset_m > 0,
            "arm dimension bore_b_offset_m = {} must be positive", bore_b_offset_m);
  }
  require(bore_diameter_m < boss_diameter_m,
          "arm bore_diameter_m = {} must be smaller than boss_diameter_m = {}", bore_diameter_m,
          boss_diameter_m);
  require(arm_thickness_m <= boss_length_m,
          "arm arm_thickness_m = {} must not exceed boss_length_m = {}", arm_thickness_m,
          boss_length_m);
  require(gripper_offset_m >= arm_depth_m / 2 + mount_thickness_m,
          "arm gripper_offset_m = {} must be at least arm_depth_m/2 + mount_thickness_m = {} (the "
          "mounting pad must sit on or above the arm plate)",
          gripper_offset_m, arm_depth_m / 2 + mount_thickness_m);
  if (with_roller) {
    require(roller_radius_m > boss_diameter_m / 2,
            "arm roller_radius_m = {} must exceed boss_diameter_m/2 = {}", roller_radius_m,
            boss_diameter_m / 2);
    require(roller_thickness_m < boss_length_m,
            "arm roller_thickness_m = {} must be smaller than boss_length_m = {}",
            roller_thickness_m, boss_length_m);
  } else {
    require(bore_b_offset_m >= boss_diameter_m / 2 && bore_b_offset_m > bore_diameter_m,
            "arm bore_b_offset_m = {} must be at least boss_diameter_m/2 = {} and more than "
            "bore_diameter_m = {} (the bores would merge or boss B reach over the arm plate)",
            bore_b_offset_m, boss_diameter_m / 2, bore_diameter_m);
  }
  const double hub_radius = with_roller ? roller_radius_m : boss_diameter_m / 2;
  const double reach = std::max(bracket_width_m, mount_length_m) / 2;
  require(length_m - reach > hub_radius,
          "arm length_m = {} must exceed max(bracket_width_m, mount_length_m)/2 + hub radius = {} "
          "(the gripper bracket and pad must clear the {})",
          length_m, reach + hub_radius, with_roller ? "roller" : "hub");
}

double ArmDimensions::volume_m3() const {
  const double pi = std::numbers::pi;
  const double big_r = boss_diameter_m / 2, rb = bore_diameter_m / 2, a = arm_depth_m / 2;
  const double t = arm_thickness_m, big_l = boss_length_m;
  double hub = 0, bores = 0, overlap = 0;
  if (with_roller) {
    const double r = roller_radius_m, e = roller_thickness_m;
    hub = pi * r * r * e + pi * big_r * big_r * (big_l - e);
    bores = pi * rb * rb * big_l;
    const double in_roller = std::min(t, e);
    overlap = in_roller * disc_strip_area(r, a) / 2 + (t - in_roller) * disc_strip_area(big_r, a) / 2;
  } else {
    hub = big_l * (pi * big_r * big_r + 2 * big_r * bore_b_offset_m);
    bores = 2 * pi * rb * rb * big_l;
    overlap = t * disc_strip_area(big_r, a) / 2;
  }
  const double plate = arm_depth_m * length_m * t - overlap;
  const double bracket =
      bracket_width_m * bracket_thickness_m * (gripper_offset_m - mount_thickness_m + a) -
      bracket_width_m / 2 * arm_depth_m * std::min(t, bracket_thickness_m);
  const double pad = mount_length_m * mount_thickness_m * mount_width_m;
  return hub - bores + plate + bracket + pad;
}

// The arm of either manipulator: C at c from A, the gripper mount at h above C.
static ArmDimensions arm_with(double c_m, double h_m, bool with_roller) {
  ArmDimensions d;
  d.with_roller = with_roller;
  d.length_m = c_m;
  d.gripper_offset_m = h_m;
  return d;
}

ArmDimensions lever_chain_arm(double c_m, double h_m, double r_m) {
  ArmDimensions d = arm_with(c_m, h_m, true);
  d.roller_radius_m = r_m;
  return d;
}

ArmDimensions lever_coupler(double c_m, double h_m, double r_m) {
  ArmDimensions d = arm_with(c_m, h_m, false);
  d.bore_b_offset_m = r_m;
  return d;
}

fem::Mesh mesh_arm(const ArmDimensions& dimensions, const MeshOptions& options) {
  dimensions.validate();
  return mesh_geometry_text("arm.geo", arm_geometry_text(), options,
      {{"Arm/with_roller", dimensions.with_roller ? 1.0 : 0.0},
       {"Arm/c", dimensions.length_m},
       {"Arm/h", dimensions.gripper_offset_m},
       {"Arm/r", dimensions.roller_radius_m},
       {"Arm/e_roller", dimensions.roller_thickness_m},
       {"Arm/d_B", dimensions.bore_b_offset_m},
       {"Arm/w", dimensions.arm_depth_m},
       {"Arm/t", dimensions.arm_thickness_m},
       {"Arm/d_bore", dimensions.bore_diameter_m},
       {"Arm/D_boss", dimensions.boss_diameter_m},
       {"Arm/L_boss", dimensions.boss_length_m},
       {"Arm/w_bracket", dimensions.bracket_width_m},
       {"Arm/t_bracket", dimensions.bracket_thickness_m},
       {"Arm/l_mount", dimensions.mount_length_m},
       {"Arm/w_mount", dimensions.mount_width_m},
       {"Arm/t_mount", dimensions.mount_thickness_m}});
}

}  // namespace kinetofem::meshes
