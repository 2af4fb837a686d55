// Video settings shared by `pronk run --video` and `pronk render`.
#pragma once

#include <optional>
#include <string>

#include "commands.h"
#include "pronk/scenario.h"
#include "pronk/schema.h"
#include "pronk/terrain.h"
#include "pronk/trace.h"
#include "pronk/world.h"
#include "render/episode_video.h"

namespace pronk::cli {

// The scenario's <render> block, overridden by the flags. Throws Error for a bad --size.
render::VideoOptions videoOptions(const Scenario& scenario, const RunOptions& options);
// The scenario's first target in the world, for the video's marker.
render::SceneMarkers markersFor(const Scenario& scenario, const World& world, const TraceSample& start);

// A jump's markers in the world: its target (relative to the trace's start, on
// the landing surface), the landing errors to show from touchdown, and the
// markers the environment declares (`schema`, may be null), read from the
// trace's metrics.
render::SceneMarkers jumpMarkers(const Trace& trace, const TargetSpec& target, std::optional<double> error_xy,
                                 std::optional<double> error_yaw, const Terrain& terrain,
                                 const Eigen::Vector3d& gravity, const EnvironmentSchema* schema);

// The terrain a jump's video draws once the apex platform of its case (`s`,
// from applyCase) appeared, from the trace's event on; nullopt when the case has
// none or the episode ended before its apex.
std::optional<render::TerrainChange> apexTerrainChange(const Scenario& s, const Terrain& terrain, const Trace& trace);

}  // namespace pronk::cli
