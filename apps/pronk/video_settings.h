// Video settings shared by `pronk run --video` and `pronk render`.
#pragma once

#include <string>

#include "commands.h"
#include "pronk/scenario.h"
#include "pronk/trace.h"
#include "pronk/world.h"
#include "render/episode_video.h"

namespace pronk::cli {

// The scenario's <render> block, overridden by the flags. Throws Error for a bad --size.
render::VideoOptions videoOptions(const Scenario& scenario, const RunOptions& options);
// Fails now, naming the file, if the video cannot be written later.
void checkWritable(const std::string& path);
// The scenario's first target in the world, for the video's marker.
render::SceneMarkers markersFor(const Scenario& scenario, const World& world, const TraceSample& start);

}  // namespace pronk::cli
