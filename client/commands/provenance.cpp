#include "client/commands/provenance.h"

namespace glint {
namespace {

struct Named {
  std::array<std::uint8_t, 3> rgb;
  const char* name;
};
constexpr std::array<Named, 8> kPalette{{{{230, 40, 40}, "red"},
                                         {{40, 200, 60}, "green"},
                                         {{50, 90, 240}, "blue"},
                                         {{240, 220, 30}, "yellow"},
                                         {{220, 50, 220}, "magenta"},
                                         {{40, 220, 230}, "cyan"},
                                         {{250, 140, 20}, "orange"},
                                         {{140, 70, 220}, "purple"}}};
constexpr int kOutline = 2;  // pixels of a re-issued tile's border

// Tints the tile's traced pixels (`mask`, empty: all).
void tint(FrameImage& image, const TileRect& r, const std::vector<std::uint8_t>& mask,
          const std::array<std::uint8_t, 3>& colour) {
  for (int y = r.y; y < r.y + r.height; ++y) {
    for (int x = r.x; x < r.x + r.width; ++x) {
      if (!mask.empty() && !maskBit(mask, static_cast<std::size_t>((y - r.y) * r.width + x - r.x))) continue;
      std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>((p[c] + colour[c]) / 2);
    }
  }
}

void outline(FrameImage& image, const TileRect& r) {
  for (int y = r.y; y < r.y + r.height; ++y) {
    for (int x = r.x; x < r.x + r.width; ++x) {
      const bool edge = x < r.x + kOutline || y < r.y + kOutline || x >= r.x + r.width - kOutline ||
                        y >= r.y + r.height - kOutline;
      if (!edge) continue;
      std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      p[0] = p[1] = p[2] = 255;
    }
  }
}

}  // namespace

std::array<std::uint8_t, 3> serverColour(std::size_t index) { return kPalette[index % kPalette.size()].rgb; }
const char* serverColourName(std::size_t index) { return kPalette[index % kPalette.size()].name; }

FrameImage provenanceImage(const FrameImage& frame, const DistributionReport& report) {
  FrameImage image = frame;
  for (std::size_t t = 0; t < report.rects.size(); ++t) {
    if (report.deliveredBy[t] < 0) continue;
    tint(image, report.rects[t], report.masks[t], serverColour(static_cast<std::size_t>(report.deliveredBy[t])));
    if (report.reissued[t]) outline(image, report.rects[t]);
  }
  return image;
}

namespace {

// "; the irradiance field's batches: red 32 (2048 probes), ...", each server
// named by its colour in the frame's legend (by its address where it has
// left the farm since).
std::string fieldBatches(const DistributionReport& report, const DistributionReport& field) {
  std::string text;
  for (const ServerReport& s : field.servers) {
    if (s.tiles == 0) continue;
    std::string name = s.address;
    for (std::size_t i = 0; i < report.servers.size(); ++i) {
      if (report.servers[i].address == s.address) name = serverColourName(i);
    }
    text += (text.empty() ? "; the irradiance field's batches: " : ", ") + name + " " + std::to_string(s.tiles) +
            " (" + std::to_string(s.probes) + " probes)";
  }
  return text;
}

}  // namespace

std::string provenanceLegend(const DistributionReport& report, const DistributionReport* field) {
  std::string legend;
  for (std::size_t i = 0; i < report.servers.size(); ++i) {
    const ServerReport& s = report.servers[i];
    if (!legend.empty()) legend += ", ";
    legend += std::string(serverColourName(i)) + " = " + s.address + " (" + std::to_string(s.tiles) + " tiles";
    if (s.joined) legend += ", new";
    if (s.state != ServerState::kOk) legend += ", " + std::string(enumWord(s.state));
    legend += ")";
  }
  if (report.reissuedTiles > 0) legend += "; outlined: " + std::to_string(report.reissuedTiles) + " tiles re-issued";
  if (report.duplicatedTiles > 0) {
    legend += "; " + std::to_string(report.duplicatedTiles) + " tiles copied to a second server (" +
              std::to_string(report.hedgedTiles) + " hedged), each tinted by the server whose copy came first";
  }
  if (field) legend += fieldBatches(report, *field);
  return legend;
}

}  // namespace glint
