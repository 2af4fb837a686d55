#include "render/scene_renderer.h"

#include <GL/gl.h>

#include <cmath>

#include <Eigen/Eigenvalues>

namespace pronk::render {
namespace {

void loadMatrix(GLenum mode, const Eigen::Matrix4d& m) {
  glMatrixMode(mode);
  glLoadMatrixd(m.data());  // Eigen is column-major, like OpenGL
}

void colour(const Eigen::Vector4d& c) { glColor4d(c(0), c(1), c(2), c(3)); }

// The sun, towards the light (directional).
const Eigen::Vector3d kSun(0.3, -0.5, 1.0);

// Soft "blob" shadows: each visual's bounding box, its corners cast along the
// sun onto the ground, becomes an ellipse (the corners' spread) whose darkness
// falls from the centre to nothing at the rim, fainter and wider the higher the
// part is. A few dozen triangles a frame: soft edges at no cost to the frame
// rate (4 planar passes with a stencil cost a third of a 720p video's rate).
constexpr double kShadowAlpha = 0.55;      // at the centre of a part on the ground
constexpr double kShadowFadeHeight = 1.2;  // m: the darkness falls by e over this height
constexpr double kShadowBlur = 0.02;       // m of soft rim beyond the part's own extent, plus 8 % of its height
constexpr double kInnerShadow = 0.55;      // the dark core's share of the radii
constexpr int kShadowSegments = 20;

}  // namespace

SceneRenderer::SceneRenderer(int width, int height, const RobotDescription& robot, const Terrain& terrain,
                             std::vector<std::string>* warnings)
    : gl_(width, height), robot_(robot), terrain_(&terrain), unit_box_(boxMesh(Eigen::Vector3d::Ones())),
      unit_sphere_(sphereMesh(1.0)), unit_cylinder_(cylinderMesh(1.0, 1.0)) {
  for (size_t b = 0; b < robot.bodies.size(); ++b) {
    for (const VisualShape& v : robot.bodies[b].visuals) {
      const TriangleMesh* mesh = nullptr;
      if (v.mesh_path) {
        mesh = meshes_.load(*v.mesh_path, v.mesh_scale);
        if (!mesh && warnings) {
          warnings->push_back("mesh '" + *v.mesh_path + "' of link '" + v.link +
                              "' could not be read; drawing a box instead");
        }
      }
      if (!mesh) {
        Shape fallback;
        fallback.type = ShapeType::Box;
        fallback.box_size = Eigen::Vector3d::Constant(0.05);
        primitives_.push_back(std::make_unique<TriangleMesh>(primitiveMesh(v.primitive ? *v.primitive : fallback)));
        mesh = primitives_.back().get();
      }
      drawables_.push_back({int(b), v.pose_body, mesh, v.rgba});
    }
  }
  // The root body's extent in its own frame, from its visuals' bounding boxes.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const Drawable& d : drawables_) {
    if (d.body != 0) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c((corner & 1) ? d.mesh->max_corner.x() : d.mesh->min_corner.x(),
                              (corner & 2) ? d.mesh->max_corner.y() : d.mesh->min_corner.y(),
                              (corner & 4) ? d.mesh->max_corner.z() : d.mesh->min_corner.z());
      const Eigen::Vector3d p = d.pose_body * c;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  if (lo.allFinite() && hi.allFinite() && (hi - lo).minCoeff() > 0) {
    // The front sixth of the trunk (at least 4 cm), 2 mm proud of its faces, so
    // that it reads from the side, from above and from ahead.
    const double depth = std::max(0.04, (hi.x() - lo.x()) / 6);
    const Eigen::Vector3d size(depth + 0.002, hi.y() - lo.y() + 0.004, hi.z() - lo.z() + 0.004);
    Eigen::Affine3d cap = Eigen::Affine3d::Identity();
    cap.translation() = Eigen::Vector3d(hi.x() + 0.002 - size.x() / 2, (lo.y() + hi.y()) / 2, (lo.z() + hi.z()) / 2);
    cap.scale(size);
    front_cap_ = cap;
  }
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::drawMesh(const TriangleMesh& mesh, const Eigen::Affine3d& pose, const Eigen::Vector4d& rgba) {
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glMultMatrixd(pose.matrix().data());
  colour(rgba);
  glVertexPointer(3, GL_FLOAT, 0, mesh.positions.data());
  glNormalPointer(GL_FLOAT, 0, mesh.normals.data());
  glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, mesh.indices.data());
  glPopMatrix();
}

void SceneRenderer::drawGround(const Eigen::Vector3d& centre) {
  if (!terrain_->hasGround()) return;
  const double z = terrain_->groundHeight();
  const double tile = 0.25;
  const int n = 32;  // 8 m x 8 m around the scene
  const double x0 = std::floor(centre.x() / tile) * tile - n * tile / 2;
  const double y0 = std::floor(centre.y() / tile) * tile - n * tile / 2;
  glNormal3d(0, 0, 1);
  glBegin(GL_QUADS);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = x0 + i * tile, y = y0 + j * tile;
      const bool dark = (int(std::floor(x / tile + 1e-9)) + int(std::floor(y / tile + 1e-9))) & 1;
      glColor3d(dark ? 0.50 : 0.58, dark ? 0.54 : 0.62, dark ? 0.50 : 0.58);
      glVertex3d(x, y, z);
      glVertex3d(x + tile, y, z);
      glVertex3d(x + tile, y + tile, z);
      glVertex3d(x, y + tile, z);
    }
  glEnd();
  // Metre lines, slightly above the tiles.
  glDisable(GL_LIGHTING);
  glColor3d(0.35, 0.38, 0.35);
  glBegin(GL_LINES);
  for (int k = 0; k <= n / 4; ++k) {
    const double x = std::round(x0) + k, y = std::round(y0) + k;
    glVertex3d(x, y0, z + 1e-3);
    glVertex3d(x, y0 + n * tile, z + 1e-3);
    glVertex3d(x0, y, z + 1e-3);
    glVertex3d(x0 + n * tile, y, z + 1e-3);
  }
  glEnd();
  glEnable(GL_LIGHTING);
}

void SceneRenderer::drawShadow(const FrameState& frame) {
  // On flat ground only: a shadow on one plane would float beyond the edge of a
  // step platform.
  if (!terrain_->hasGround() || !terrain_->boxes().empty()) return;
  const double ground = terrain_->groundHeight();
  const Eigen::Vector3d sun = kSun.normalized();
  glDisable(GL_LIGHTING);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  glMatrixMode(GL_MODELVIEW);
  for (const Drawable& d : drawables_) {
    if (d.body >= int(frame.body_poses.size())) continue;
    const Eigen::Isometry3d pose = frame.body_poses[d.body] * d.pose_body;
    // The box's corners in the world, cast along the sun onto the ground.
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
    Eigen::Vector2d cast[8];
    double height = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d local((c & 1) ? d.mesh->max_corner.x() : d.mesh->min_corner.x(),
                                  (c & 2) ? d.mesh->max_corner.y() : d.mesh->min_corner.y(),
                                  (c & 4) ? d.mesh->max_corner.z() : d.mesh->min_corner.z());
      const Eigen::Vector3d p = pose * local;
      const double up = std::max(0.0, p.z() - ground);
      cast[c] = p.head<2>() - up / sun.z() * sun.head<2>();
      mean += cast[c] / 8.0;
      height += up / 8.0;
    }
    for (const Eigen::Vector2d& q : cast) spread += (q - mean) * (q - mean).transpose() / 8.0;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(spread);
    const double blur = kShadowBlur + 0.08 * height;
    const Eigen::Vector2d a = axes.eigenvectors().col(0) * (std::sqrt(std::max(0.0, axes.eigenvalues()(0))) + blur);
    const Eigen::Vector2d b = axes.eigenvectors().col(1) * (std::sqrt(std::max(0.0, axes.eigenvalues()(1))) + blur);
    const double alpha = kShadowAlpha * std::exp(-height / kShadowFadeHeight);
    const double z = ground + 1.5e-3;
    // A dark core to kInnerShadow of the radii, then a fall to nothing at the rim.
    auto ring = [&](double scale, int k) {
      const double t = 2.0 * M_PI * k / kShadowSegments;
      const Eigen::Vector2d q = mean + scale * (std::cos(t) * a + std::sin(t) * b);
      glVertex3d(q.x(), q.y(), z);
    };
    glBegin(GL_TRIANGLE_FAN);
    glColor4d(0.05, 0.05, 0.08, alpha);
    glVertex3d(mean.x(), mean.y(), z);
    glColor4d(0.05, 0.05, 0.08, 0.85 * alpha);
    for (int k = 0; k <= kShadowSegments; ++k) ring(kInnerShadow, k);
    glEnd();
    glBegin(GL_QUAD_STRIP);
    for (int k = 0; k <= kShadowSegments; ++k) {
      glColor4d(0.05, 0.05, 0.08, 0.85 * alpha);
      ring(kInnerShadow, k);
      glColor4d(0.05, 0.05, 0.08, 0.0);
      ring(1.0, k);
    }
    glEnd();
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glEnable(GL_LIGHTING);
}

void SceneRenderer::render(const Camera& camera, const SceneMarkers& markers, const FrameState& frame,
                           std::vector<uint8_t>& rgba) {
  gl_.makeCurrent();
  glViewport(0, 0, gl_.width(), gl_.height());
  glClearColor(float(kSkyColour.x()), float(kSkyColour.y()), float(kSkyColour.z()), 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_NORMALIZE);
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glShadeModel(GL_SMOOTH);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);

  loadMatrix(GL_PROJECTION, perspective(camera.fovy_deg, double(gl_.width()) / gl_.height(), 0.05, 100));
  loadMatrix(GL_MODELVIEW, lookAt(camera));
  // A sun from above and behind the camera, and a weaker fill light.
  const GLfloat sun[] = {float(kSun.x()), float(kSun.y()), float(kSun.z()), 0.0f}, sun_colour[] = {0.75f, 0.75f, 0.72f, 1};
  const GLfloat fill[] = {-0.6f, 0.8f, 0.4f, 0.0f}, fill_colour[] = {0.25f, 0.27f, 0.3f, 1};
  const GLfloat ambient[] = {0.28f, 0.28f, 0.3f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, sun);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, sun_colour);
  glLightfv(GL_LIGHT1, GL_POSITION, fill);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_colour);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);

  drawGround(camera.target);
  for (const TerrainBox& b : terrain_->boxes()) {
    Eigen::Affine3d pose = Eigen::Affine3d::Identity();
    pose.translation() = Eigen::Vector3d(b.position[0], b.position[1], b.position[2]);
    pose.linear() = Eigen::AngleAxisd(b.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.scale(Eigen::Vector3d(b.size[0], b.size[1], b.size[2]));
    drawMesh(unit_box_, pose, Eigen::Vector4d(0.62, 0.5, 0.36, 1));
  }

  if (markers.target) {
    // A flat disc with a yaw arrow, lit flat so its colour reads exactly.
    glDisable(GL_LIGHTING);
    Eigen::Affine3d disc = Eigen::Affine3d::Identity();
    disc.translation() = *markers.target + Eigen::Vector3d(0, 0, 0.004);
    disc.scale(Eigen::Vector3d(0.09, 0.09, 0.006));
    drawMesh(unit_cylinder_, disc, Eigen::Vector4d(kTargetColour.x(), kTargetColour.y(), kTargetColour.z(), 1));
    Eigen::Affine3d arrow = Eigen::Affine3d::Identity();
    arrow.translation() = *markers.target + Eigen::Vector3d(0.12 * std::cos(markers.target_yaw),
                                                            0.12 * std::sin(markers.target_yaw), 0.006);
    arrow.linear() = Eigen::AngleAxisd(markers.target_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    arrow.scale(Eigen::Vector3d(0.2, 0.025, 0.006));
    drawMesh(unit_box_, arrow, Eigen::Vector4d(kTargetColour.x(), kTargetColour.y(), kTargetColour.z(), 1));
    glEnable(GL_LIGHTING);
  }

  drawShadow(frame);
  for (const Drawable& d : drawables_) {
    if (d.body >= int(frame.body_poses.size())) continue;
    drawMesh(*d.mesh, Eigen::Affine3d((frame.body_poses[d.body] * d.pose_body).matrix()), d.rgba);
  }
  if (front_cap_ && !frame.body_poses.empty()) {
    drawMesh(unit_box_, Eigen::Affine3d(frame.body_poses[0].matrix()) * *front_cap_,
             Eigen::Vector4d(kFrontColour.x(), kFrontColour.y(), kFrontColour.z(), 1));
  }
  // Feet on the ground get a green disc under them.
  for (size_t f = 0; f < frame.foot_positions.size() && f < frame.foot_in_contact.size(); ++f) {
    if (!frame.foot_in_contact[f]) continue;
    const Eigen::Vector3d& p = frame.foot_positions[f];
    const auto top = terrain_->surfaceBelow(p.x(), p.y(), p.z());
    Eigen::Affine3d disc = Eigen::Affine3d::Identity();
    disc.translation() = Eigen::Vector3d(p.x(), p.y(), (top ? top->height : 0.0) + 0.002);
    disc.scale(Eigen::Vector3d(0.04, 0.04, 0.003));
    glDisable(GL_LIGHTING);
    drawMesh(unit_cylinder_, disc, Eigen::Vector4d(0.1, 0.75, 0.25, 1));
    glEnable(GL_LIGHTING);
  }
  // The planned CoM arc: solid where it is in sight, dashed and thin over what
  // hides it, as hidden lines are drawn. It is the CoM's path, so it runs
  // through the trunk; for short jumps the robot's own body would hide all of it.
  if (markers.planned_arc.size() > 1) {
    glDisable(GL_LIGHTING);
    glColor3d(kArcColour.x(), kArcColour.y(), kArcColour.z());
    const auto strip = [&] {
      glBegin(GL_LINE_STRIP);
      for (const Eigen::Vector3d& p : markers.planned_arc) glVertex3d(p.x(), p.y(), p.z());
      glEnd();
    };
    glLineWidth(3);
    strip();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_LINE_STIPPLE);
    glLineStipple(2, 0x0F0F);
    glLineWidth(1.5);
    strip();
    glDisable(GL_LINE_STIPPLE);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_LIGHTING);
  }
  // The predicted landing goes on top of everything: the robot lands on it.
  glDisable(GL_DEPTH_TEST);
  if (markers.predicted_landing) {
    Eigen::Affine3d dot = Eigen::Affine3d::Identity();
    dot.translation() = *markers.predicted_landing;
    dot.scale(0.025);
    drawMesh(unit_sphere_, dot, Eigen::Vector4d(kArcColour.x(), kArcColour.y(), kArcColour.z(), 1));
  }
  glEnable(GL_DEPTH_TEST);
  gl_.readPixels(rgba);
}

}  // namespace pronk::render
