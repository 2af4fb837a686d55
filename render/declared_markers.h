// The markers an environment declares (plugin ABI 1.3, pronk/schema.h) placed
// in the world for a recorded episode: a ballistic arc and a point, their
// numbers read from the trace's metrics. The renderer names no metric itself.
#pragma once

#include <Eigen/Core>

#include "pronk/schema.h"
#include "pronk/terrain.h"
#include "pronk/trace.h"
#include "render/scene_renderer.h"

namespace pronk::render {

// Adds the first declared arc (planned_arc) and point (predicted_landing) to
// `markers`. Their start frame: origin on the surface below the CoM of the
// trace's first sample, x along the trunk's heading there. A marker whose
// numbers the episode did not report (or reported as NaN) is left out.
void addDeclaredMarkers(SceneMarkers& markers, const Trace& trace, const EnvironmentSchema& schema,
                        const Terrain& terrain, const Eigen::Vector3d& gravity);

}  // namespace pronk::render
