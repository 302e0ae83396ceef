// The --stats record names what it measured: the BVH build in process, the
// connection (connect, upload, the server's build) through a glintd, and the
// network's share of tracing only where there is a network.
#include "client/commands/stats_json.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(StatsJson, InProcessRecordHasNoNetwork) {
  FrameRecord r;
  r.maskedPixels = 32;
  r.prepareMs = 1.5;
  r.hybrid = HybridTimes{};
  const nlohmann::json j = toJson(r);
  EXPECT_EQ(j["bvh_ms"], 1.5);
  EXPECT_FALSE(j.contains("connect_ms"));
  EXPECT_FALSE(j.contains("network_ms"));
  EXPECT_TRUE(j.contains("raster_ms"));
  EXPECT_EQ(j["masked_pixels"], 32);
}

// 100 of 400 pixels traced, with 300 camera rays of the 1,600 a 4-sample
// full trace casts.
TEST(StatsJson, SharesOfTheFullTrace) {
  FrameRecord r;
  r.width = 20;
  r.height = 20;
  r.samples = 4;
  r.maskedPixels = 100;
  r.rays.primary = 300;
  nlohmann::json j = toJson(r);
  EXPECT_DOUBLE_EQ(j["traced_share"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(j["primary_share"].get<double>(), 300.0 / 1600.0);
  r.crop = TileRect{0, 0, 10, 10};  // of the window rendered
  j = toJson(r);
  EXPECT_DOUBLE_EQ(j["traced_share"].get<double>(), 1.0);
}

// Path transport's counts appear only when paths were traced.
TEST(StatsJson, PathsAreCountedWhereThereAreAny) {
  FrameRecord r;
  EXPECT_FALSE(toJson(r).contains("paths"));
  r.rays.paths = 4;
  r.rays.pathBounces = 10;
  r.rays.reflection = 25;  // Whitted's mirror rays among them, in a frame that reads a field
  r.rays.refraction = 1;
  r.rays.longestPath = 5;
  r.rays.lightSamples = 12;
  const nlohmann::json paths = toJson(r)["paths"];
  EXPECT_EQ(paths["count"], 4);
  EXPECT_DOUBLE_EQ(paths["bounces_mean"].get<double>(), 2.5);
  EXPECT_EQ(paths["bounces_max"], 5);
  EXPECT_EQ(paths["light_samples"], 12);
}

// The irradiance field's fill is a record of its own: its probes, time and
// rays, none of them the frame's or the BVH's.
TEST(StatsJson, TheFieldsFillIsApartFromTheFrame) {
  FrameRecord r;
  r.prepareMs = 0.25;
  r.rays.paths = 10;
  EXPECT_FALSE(toJson(r).contains("field"));
  r.field = FrameRecord::Field{512, 256, 317.0, {}};
  r.field->rays.primary = 512 * 256;
  r.field->rays.paths = 512 * 256;
  const nlohmann::json j = toJson(r);
  EXPECT_EQ(j["bvh_ms"], 0.25);
  EXPECT_EQ(j["field"]["probes"], 512);
  EXPECT_EQ(j["field"]["rays_a_probe"], 256);
  EXPECT_EQ(j["field"]["ms"], 317.0);
  EXPECT_EQ(j["field"]["rays"]["primary"], 512 * 256);
  EXPECT_EQ(j["paths"]["count"], 10);
}

TEST(StatsJson, RemoteRecordNamesTheConnection) {
  FrameRecord r;
  r.remote = true;
  r.prepareMs = 7.0;
  EXPECT_EQ(toJson(r)["connect_ms"], 7.0);
  EXPECT_FALSE(toJson(r).contains("bvh_ms"));
  EXPECT_FALSE(toJson(r).contains("network_ms"));  // a full trace measures no network share
  r.hybrid = HybridTimes{};
  r.hybrid->networkMs = 0.25;
  EXPECT_EQ(toJson(r)["network_ms"], 0.25);
}

}  // namespace
}  // namespace glint
