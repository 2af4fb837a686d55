// A Go1 platform built in code (no scenario file), for physics tests.
#pragma once

#include <string>

#include "pronk/scenario.h"
#include "pronk/terrain.h"
#include "pronk/world.h"

namespace pronk::testing {

inline std::string robotUrdf(const std::string& name) {
  return std::string(PRONK_SOURCE_DIR) + "/assets/robots/" + name + "/" + name + ".urdf";
}

inline PlatformSpec quadrupedPlatform(const std::string& urdf) {
  PlatformSpec p;
  p.name = "test";
  p.urdf = urdf;
  p.feet = {"FR_foot", "FL_foot", "RR_foot", "RL_foot"};
  p.stance = {0, 0.75, -1.5};
  p.joints.kp = 100;
  p.joints.kd = 2;
  return p;
}

}  // namespace pronk::testing
