#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "client/farm/distribution_report.h"
#include "common/render/frame.h"

namespace glint {

// The colour that marks server `index` in provenance images, and its name
// for the legend ("red", "green" ...; the palette repeats after eight).
std::array<std::uint8_t, 3> serverColour(std::size_t index);
const char* serverColourName(std::size_t index);

// Who traced what: the frame with every traced pixel half-tinted with the
// colour of the server that delivered its tile, and a white outline around
// tiles that were re-issued after their first server was lost. Pixels
// OpenGL drew are left as drawn.
FrameImage provenanceImage(const FrameImage& frame, const DistributionReport& report);

// "red = 127.0.0.1:7001 (41 tiles), green = ..." with servers that joined,
// left or were lost named, and the tiles re-issued and copied; with the
// report of an irradiance field's fill (`field`), each server's batches of it.
std::string provenanceLegend(const DistributionReport& report, const DistributionReport* field = nullptr);

}  // namespace glint
