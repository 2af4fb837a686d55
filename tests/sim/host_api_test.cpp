// The host's services to a plugin (pronk_host_api) against the World they
// describe: the terrain's top surface under a point (ABI 1.6).
#include <gtest/gtest.h>

#include <cmath>

#include "go1_fixture.h"
#include "pronk/controller.h"
#include "pronk/world.h"

namespace pronk {
namespace {

using testing::quadrupedPlatform;
using testing::robotUrdf;

TerrainBox box(const std::string& name, Vec3 size, Vec3 position, double yaw = 0) {
  TerrainBox b;
  b.name = name;
  b.size = size;
  b.position = position;
  b.yaw = yaw;
  return b;
}

World makeWorld(const Terrain& terrain) {
  const std::string urdf = robotUrdf("go1");
  return World(loadUrdf(urdf, UrdfOptions{}), quadrupedPlatform(urdf), SimSpec{}, terrain);
}

struct Top {
  pronk_status status;
  double height;
  int32_t surface;
};

Top topAt(const pronk_host_api* api, double x, double y) {
  Top t{PRONK_OK, -99.0, -99};
  t.status = api->terrain_top(api->host, x, y, &t.height, &t.surface);
  return t;
}

TEST(HostApi, TerrainTopIsTheHighestBoxOverTheGround) {
  // A 0.3 m box 1 m ahead, a 0.2 m box turned 45 deg to the left, and a 0.1 m
  // slab on top of the first box's front half; the ground 0.05 m below zero.
  const World world = makeWorld(Terrain(true, -0.05,
                                        {box("step", {1.0, 1.0, 0.3}, {1.5, 0, 0.1}),
                                         box("diamond", {0.4, 0.4, 0.2}, {0, 1.5, 0.05}, M_PI / 4),
                                         box("slab", {0.5, 1.0, 0.1}, {1.25, 0, 0.3})}));
  const HostApi host(world, nullptr);
  const pronk_host_api* api = host.api();
  ASSERT_GE(api->struct_size, offsetof(pronk_host_api, terrain_top) + sizeof(api->terrain_top));

  Top t = topAt(api, 0.2, 0.0);
  EXPECT_EQ(t.status, PRONK_OK);
  EXPECT_DOUBLE_EQ(t.height, -0.05);
  EXPECT_EQ(t.surface, -1);

  t = topAt(api, 1.9, 0.3);  // the step's rear half: its top at 0.1 + 0.15
  EXPECT_EQ(t.status, PRONK_OK);
  EXPECT_DOUBLE_EQ(t.height, 0.25);
  EXPECT_EQ(t.surface, 0);

  t = topAt(api, 1.1, -0.4);  // the slab on the step's front half: 0.3 + 0.05
  EXPECT_DOUBLE_EQ(t.height, 0.35);
  EXPECT_EQ(t.surface, 2);

  // The diamond's corner lies 0.2 sqrt(2) = 0.283 m from its centre along y:
  // inside at 0.27, outside at 0.29 (an axis-aligned box would end at 0.2).
  t = topAt(api, 0.0, 1.5 + 0.27);
  EXPECT_DOUBLE_EQ(t.height, 0.15);
  EXPECT_EQ(t.surface, 1);
  t = topAt(api, 0.0, 1.5 + 0.29);
  EXPECT_EQ(t.surface, -1);
  t = topAt(api, 0.19, 1.5 + 0.19);  // inside an axis-aligned box, outside the turned one
  EXPECT_EQ(t.surface, -1);

  // Either output may be NULL.
  double height = 0;
  EXPECT_EQ(api->terrain_top(api->host, 1.9, 0.0, &height, nullptr), PRONK_OK);
  EXPECT_DOUBLE_EQ(height, 0.25);
  int32_t surface = -7;
  EXPECT_EQ(api->terrain_top(api->host, 1.9, 0.0, nullptr, &surface), PRONK_OK);
  EXPECT_EQ(surface, 0);
  EXPECT_EQ(api->terrain_top(api->host, NAN, 0.0, &height, &surface), PRONK_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(api->terrain_top(api->host, 0.0, INFINITY, &height, &surface), PRONK_ERROR_INVALID_ARGUMENT);
}

TEST(HostApi, TerrainTopOverNothingIsUnsupportedAndLeavesTheOutputs) {
  const World world = makeWorld(Terrain(false, 0, {box("island", {1.0, 1.0, 0.2}, {0, 0, -0.1})}));
  const HostApi host(world, nullptr);
  const pronk_host_api* api = host.api();
  Top t = topAt(api, 0.1, 0.1);
  EXPECT_EQ(t.status, PRONK_OK);
  EXPECT_DOUBLE_EQ(t.height, 0.0);
  EXPECT_EQ(t.surface, 0);
  t = topAt(api, 3.0, 0.0);
  EXPECT_EQ(t.status, PRONK_ERROR_UNSUPPORTED);
  EXPECT_EQ(t.height, -99.0);
  EXPECT_EQ(t.surface, -99);
}

}  // namespace
}  // namespace pronk
