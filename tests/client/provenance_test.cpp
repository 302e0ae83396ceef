// The provenance legend says everything the frame's report says of its
// servers: tiles each, who joined, left or was lost, tiles re-issued and
// copied, and each server's batches of an irradiance field.
#include "client/commands/provenance.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Provenance, TheLegendNamesEveryServersPartAndTheCopies) {
  DistributionReport report;
  report.servers.resize(3);
  report.servers[0].address = "10.0.0.1:7878";
  report.servers[0].tiles = 40;
  report.servers[1].address = "10.0.0.2:7878";
  report.servers[1].tiles = 0;
  report.servers[1].state = ServerState::kLeft;
  report.servers[2].address = "10.0.0.3:7878";
  report.servers[2].tiles = 12;
  report.servers[2].joined = true;
  report.reissuedTiles = 2;
  report.duplicatedTiles = 5;
  report.hedgedTiles = 3;
  EXPECT_EQ(provenanceLegend(report),
            "red = 10.0.0.1:7878 (40 tiles), green = 10.0.0.2:7878 (0 tiles, left), "
            "blue = 10.0.0.3:7878 (12 tiles, new); outlined: 2 tiles re-issued; 5 tiles copied to a second server "
            "(3 hedged), each tinted by the server whose copy came first");
}

TEST(Provenance, TheLegendNamesEachServersBatchesOfTheField) {
  DistributionReport report;
  report.servers.resize(2);
  report.servers[0].address = "10.0.0.1:7878";
  report.servers[0].tiles = 30;
  report.servers[1].address = "10.0.0.3:7878";
  report.servers[1].tiles = 10;
  DistributionReport field;  // filled before the frame, by a server that has left since
  field.servers.resize(3);
  field.servers[0].address = "10.0.0.3:7878";
  field.servers[0].tiles = 5;
  field.servers[0].probes = 320;
  field.servers[1].address = "10.0.0.2:7878";
  field.servers[1].tiles = 3;
  field.servers[1].probes = 192;
  field.servers[2].address = "10.0.0.1:7878";  // sent no batch
  EXPECT_EQ(provenanceLegend(report, &field),
            "red = 10.0.0.1:7878 (30 tiles), green = 10.0.0.3:7878 (10 tiles); the irradiance field's batches: "
            "green 5 (320 probes), 10.0.0.2:7878 3 (192 probes)");
}

}  // namespace
}  // namespace glint
