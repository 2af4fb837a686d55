#include "render/scene_renderer.h"

#include <GL/gl.h>

#include <cmath>

namespace pronk::render {
namespace {

void loadMatrix(GLenum mode, const Eigen::Matrix4d& m) {
  glMatrixMode(mode);
  glLoadMatrixd(m.data());  // Eigen is column-major, like OpenGL
}

void colour(const Eigen::Vector4d& c) { glColor4d(c(0), c(1), c(2), c(3)); }

}  // namespace

SceneRenderer::SceneRenderer(int width, int height, const RobotDescription& robot, const Terrain& terrain,
                             std::vector<std::string>* warnings)
    : gl_(width, height), robot_(robot), terrain_(terrain), unit_box_(boxMesh(Eigen::Vector3d::Ones())),
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
  if (!terrain_.hasGround()) return;
  const double z = terrain_.groundHeight();
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
  const GLfloat sun[] = {0.3f, -0.5f, 1.0f, 0.0f}, sun_colour[] = {0.75f, 0.75f, 0.72f, 1};
  const GLfloat fill[] = {-0.6f, 0.8f, 0.4f, 0.0f}, fill_colour[] = {0.25f, 0.27f, 0.3f, 1};
  const GLfloat ambient[] = {0.28f, 0.28f, 0.3f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, sun);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, sun_colour);
  glLightfv(GL_LIGHT1, GL_POSITION, fill);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_colour);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);

  drawGround(camera.target);
  for (const TerrainBox& b : terrain_.boxes()) {
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

  for (const Drawable& d : drawables_) {
    if (d.body >= int(frame.body_poses.size())) continue;
    drawMesh(*d.mesh, Eigen::Affine3d((frame.body_poses[d.body] * d.pose_body).matrix()), d.rgba);
  }
  // Feet on the ground get a green disc under them.
  for (size_t f = 0; f < frame.foot_positions.size() && f < frame.foot_in_contact.size(); ++f) {
    if (!frame.foot_in_contact[f]) continue;
    const Eigen::Vector3d& p = frame.foot_positions[f];
    const auto top = terrain_.surfaceBelow(p.x(), p.y(), p.z());
    Eigen::Affine3d disc = Eigen::Affine3d::Identity();
    disc.translation() = Eigen::Vector3d(p.x(), p.y(), (top ? top->height : 0.0) + 0.002);
    disc.scale(Eigen::Vector3d(0.04, 0.04, 0.003));
    glDisable(GL_LIGHTING);
    drawMesh(unit_cylinder_, disc, Eigen::Vector4d(0.1, 0.75, 0.25, 1));
    glEnable(GL_LIGHTING);
  }
  // The planned CoM arc and its predicted landing go on top of everything: the
  // arc runs through the trunk (it is the CoM's path), and for short jumps the
  // robot's own body would hide all of it.
  glDisable(GL_DEPTH_TEST);
  if (markers.planned_arc.size() > 1) {
    glDisable(GL_LIGHTING);
    glLineWidth(3);
    glColor3d(kArcColour.x(), kArcColour.y(), kArcColour.z());
    glBegin(GL_LINE_STRIP);
    for (const Eigen::Vector3d& p : markers.planned_arc) glVertex3d(p.x(), p.y(), p.z());
    glEnd();
    glEnable(GL_LIGHTING);
  }
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
