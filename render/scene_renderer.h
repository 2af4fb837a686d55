// Draws one frame of an episode with legacy OpenGL into an OSMesa buffer:
// sky, a checkered ground with a grid, terrain boxes, the robot's URDF visuals
// (meshes through assimp, primitives otherwise), the target with a yaw arrow,
// a planned arc and foot contact markers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pronk/robot_description.h"
#include "pronk/terrain.h"
#include "render/camera.h"
#include "render/mesh_library.h"
#include "render/offscreen_gl.h"

namespace pronk::render {

// What changes from frame to frame.
struct FrameState {
  std::vector<Eigen::Isometry3d> body_poses;  // one per RobotDescription body
  std::vector<Eigen::Vector3d> foot_positions;
  std::vector<uint8_t> foot_in_contact;
};

// Markers that stay the same over an episode.
struct SceneMarkers {
  std::optional<Eigen::Vector3d> target;       // world position of the target
  double target_yaw = 0;                        // rad
  std::vector<Eigen::Vector3d> planned_arc;     // polyline, world
  std::optional<Eigen::Vector3d> predicted_landing;
  std::string arc_label = "planned flight", landing_label = "predicted landing";  // the video's legend
  // Shown from touchdown to the end (default: CoM to target, horizontal, at the end).
  std::optional<double> landing_error;          // m
  std::optional<double> landing_yaw_error;      // rad
};

// Colours the tests look for.
inline const Eigen::Vector3d kTargetColour{0.9, 0.08, 0.08};
inline const Eigen::Vector3d kSkyColour{0.72, 0.82, 0.93};
inline const Eigen::Vector3d kArcColour{0.95, 0.65, 0.1};  // planned CoM arc, predicted landing
inline const Eigen::Vector3d kFrontColour{0.1, 0.8, 0.9};  // the trunk's front face: which way the robot looks

class SceneRenderer {
 public:
  // Prepares the meshes of every visual. A visual mesh that cannot be read is
  // drawn as the description's primitive fallback, with one warning in `warnings`.
  SceneRenderer(int width, int height, const RobotDescription& robot, const Terrain& terrain,
                std::vector<std::string>* warnings = nullptr);
  ~SceneRenderer();

  // Renders and returns the frame, RGBA, rows top to bottom.
  void render(const Camera& camera, const SceneMarkers& markers, const FrameState& frame,
              std::vector<uint8_t>& rgba);
  // Draws `terrain` from the next frame on (it must outlive the renderer's use of it).
  void setTerrain(const Terrain& terrain) { terrain_ = &terrain; }
  int width() const { return gl_.width(); }
  int height() const { return gl_.height(); }

 private:
  struct Drawable {
    int body;
    Eigen::Isometry3d pose_body;
    const TriangleMesh* mesh;
    Eigen::Vector4d rgba;
  };
  void drawMesh(const TriangleMesh& mesh, const Eigen::Affine3d& pose, const Eigen::Vector4d& rgba);
  // A cap over the front end of the root body's visuals (its +x end), in the
  // root body's frame; none when the root body has no visual.
  std::optional<Eigen::Affine3d> front_cap_;
  void drawGround(const Eigen::Vector3d& centre);
  // The robot's soft blob shadows from the sun on flat ground (none with step platforms).
  void drawShadow(const FrameState& frame);

  OffscreenGl gl_;
  const RobotDescription& robot_;
  const Terrain* terrain_;
  MeshLibrary meshes_;
  std::vector<std::unique_ptr<TriangleMesh>> primitives_;
  std::vector<Drawable> drawables_;
  TriangleMesh unit_box_, unit_sphere_, unit_cylinder_;
};

}  // namespace pronk::render
