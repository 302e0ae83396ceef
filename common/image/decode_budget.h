#pragma once

#include <cstddef>
#include <string>

namespace glint {

// What decoding an image may take, asked before each allocation a file
// decides (image_decode.h): its size against a pixel limit, then the bytes
// it keeps and those its decoder holds meanwhile. Each call throws an
// InputError naming `place` to refuse. The scene's loader answers with its
// SceneBudget; a tool reading one local file, with PixelLimit.
class DecodeBudget {
 public:
  virtual ~DecodeBudget() = default;

  virtual std::size_t maxTexturePixels() const = 0;
  // The image the decode returns: width x height texels of bytesPerTexel.
  virtual void chargeImage(int width, int height, const std::string& place, std::size_t bytesPerTexel) = 0;
  // Bytes held `when` (until refund()).
  virtual void charge(std::size_t bytes, const std::string& place, const char* when) = 0;
  virtual void refund(std::size_t bytes) = 0;
};

// A budget of pixels alone: memory is not counted.
class PixelLimit final : public DecodeBudget {
 public:
  explicit PixelLimit(std::size_t maxPixels) : maxPixels_(maxPixels) {}

  std::size_t maxTexturePixels() const override { return maxPixels_; }
  void chargeImage(int, int, const std::string&, std::size_t) override {}
  void charge(std::size_t, const std::string&, const char*) override {}
  void refund(std::size_t) override {}

 private:
  std::size_t maxPixels_;
};

// The largest texture a scene may hold unless told otherwise (8192 x 8192).
constexpr std::size_t kDefaultMaxTexturePixels = std::size_t{1} << 26;

}  // namespace glint
