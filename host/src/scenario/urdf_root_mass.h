// The mass of a URDF's root body, so that a negative trunk_mass_offset can be
// refused while the scenario is read, with the file and line of the offset.
#pragma once

#include <optional>
#include <string>

namespace pronk::scenario_file {

struct RootBody {
  std::string link;  // the root link's name
  double mass = 0;   // kg: the root link plus every link joined to it by fixed joints
};

// Reads only <link>/<inertial>/<mass> and <joint> parent/child/type. Returns
// nullopt when the file is not a URDF this can read (no single root, bad XML):
// the model loader reports those problems itself.
std::optional<RootBody> urdfRootBody(const std::string& urdf_path);

}  // namespace pronk::scenario_file
