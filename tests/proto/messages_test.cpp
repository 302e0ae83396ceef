#include "proto/messages.h"

#include <cstring>
#include <deque>

#include <gtest/gtest.h>

#include "common/base/error.h"
#include "tests/support/test_support.h"

namespace glint::proto {
namespace {

// The message in `frame`. The message points into the bytes, so they are
// kept to the end of the test program (the encoders return temporaries), and
// placed so that the message after the 4-byte length starts 8-aligned, as
// FlatBuffers' 8-byte fields need.
const wire::Message& decode(const std::vector<std::uint8_t>& frame) {
  static std::deque<std::vector<std::uint64_t>> kept;  // growing never moves an element
  kept.emplace_back(frame.size() / sizeof(std::uint64_t) + 2);
  std::uint8_t* bytes = reinterpret_cast<std::uint8_t*>(kept.back().data()) + (sizeof(std::uint64_t) - kHeaderBytes);
  std::memcpy(bytes, frame.data(), frame.size());
  static std::vector<std::uint64_t> unused;  // the message lies aligned already
  const Decoded d = decodeFrame({bytes, frame.size()}, kDefaultMaxMessageBytes, unused);
  EXPECT_EQ(d.status, DecodeStatus::kGood) << d.error;
  return *d.message;
}

SceneHash someHash() {
  SceneHash h{};
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = static_cast<std::uint8_t>(i * 7 + 1);
  return h;
}

FrameSettings someFrame() {
  FrameSettings f;
  f.width = 320;
  f.height = 200;
  f.camera = {{1, 2, 3}, {0, 0.5f, 0}, {0, 1, 0}, 40.0f};
  f.sampling = {SamplePattern::kJittered, 5, FilterType::kMitchell, 77};
  f.tracing.maxDepth = 7;
  f.tracing.minWeight = 0.02f;
  return f;
}

TEST(Messages, HelloErrorAndGoodbyeRoundTrip) {
  {
    const auto* m = decode(encodeHello(1234, 8, "glintd")).body_as_Hello();
    ASSERT_TRUE(m);
    EXPECT_EQ(m->protocol_version(), kProtocolVersion);
    EXPECT_EQ(m->max_message_bytes(), 1234u);
    EXPECT_EQ(m->threads(), 8u);
    EXPECT_EQ(m->software()->str(), "glintd");
  }
  {
    const auto* m = decode(encodeError(wire::ErrorCode::BadScene, "objects[1].radius: must be > 0", 2, 5)).body_as_Error();
    EXPECT_EQ(m->code(), wire::ErrorCode::BadScene);
    EXPECT_EQ(m->message()->str(), "objects[1].radius: must be > 0");
  }
  EXPECT_TRUE(decode(encodeGoodbye()).body_as_Goodbye());
}

TEST(Messages, SceneMessagesRoundTrip) {
  const SceneHash h = someHash();
  EXPECT_EQ(decodeHash(decode(encodeSceneQuery(h)).body_as_SceneQuery()->hash(), "hash"), h);
  {
    const auto* m = decode(encodeSceneStatus(h, true)).body_as_SceneStatus();
    EXPECT_EQ(decodeHash(m->hash(), "hash"), h);
    EXPECT_TRUE(m->present());
  }
  {
    const SceneBundle bundle{"{\"glint\": 1}", {{"m/a.obj", "v 0 0 0\n"}, {"t.png", std::string("\0\1\2", 3)}}};
    const auto* m = decode(encodeSceneUpload(bundle.hash(), bundle)).body_as_SceneUpload();
    EXPECT_EQ(decodeHash(m->hash(), "hash"), bundle.hash());
    const SceneManifest back = decodeManifest(*m);
    EXPECT_EQ(back.text, bundle.text);
    ASSERT_EQ(back.files.size(), 2u);
    EXPECT_EQ(back.files[0], std::make_pair(std::string("m/a.obj"), sha256("v 0 0 0\n")));
    EXPECT_EQ(back.files[1], std::make_pair(std::string("t.png"), sha256(std::string("\0\1\2", 3))));
    const std::vector<SceneHash> hashes = digest(bundle).files;
    const auto* q = decode(encodeSceneQuery(bundle.hash(), hashes)).body_as_SceneQuery();
    EXPECT_EQ(decodeFileHashes(*q, 2), hashes);
    EXPECT_THROW(decodeFileHashes(*q, 1), InputError);  // more files than allowed
    const std::vector<std::uint32_t> missing{1};
    const auto* st = decode(encodeSceneStatus(h, false, missing)).body_as_SceneStatus();
    EXPECT_EQ(std::vector<std::uint32_t>(st->missing()->begin(), st->missing()->end()), missing);
  }
  {  // a file in pieces: each piece's offset and the whole size; an empty file is one empty piece
    const std::string bytes(10, 'x');
    const auto chunks = encodeFileChunks(bytes, sha256(bytes), 4);
    ASSERT_EQ(chunks.size(), 3u);
    const auto* last = decode(chunks[2]).body_as_FileChunk();
    EXPECT_EQ(last->size(), 10u);
    EXPECT_EQ(last->offset(), 8u);
    EXPECT_EQ(last->data()->size(), 2u);
    EXPECT_EQ(decodeHash32(last->hash(), "hash"), sha256(bytes));
    EXPECT_EQ(encodeFileChunks("", sha256(""), 4).size(), 1u);
  }
  EXPECT_FLOAT_EQ(decode(encodeSceneReady(h, 12.5f)).body_as_SceneReady()->build_ms(), 12.5f);
}

TEST(Messages, FrameSetupRoundTrips) {
  const SceneHash h = someHash();
  {
    const FrameSettings f = someFrame();
    const auto* m = decode(encodeFrameSetup(9, h, f)).body_as_FrameSetup();
    EXPECT_EQ(m->frame_id(), 9u);
    const FrameSettings back = decodeFrameSettings(*m, 1 << 28);
    EXPECT_EQ(back.width, f.width);
    EXPECT_EQ(back.height, f.height);
    EXPECT_EQ(back.camera.eye, f.camera.eye);
    EXPECT_EQ(back.camera.lookAt, f.camera.lookAt);
    EXPECT_EQ(back.camera.up, f.camera.up);
    EXPECT_EQ(back.camera.fovY, f.camera.fovY);
    EXPECT_EQ(back.sampling.pattern, f.sampling.pattern);
    EXPECT_EQ(back.sampling.samples, f.sampling.samples);
    EXPECT_EQ(back.sampling.filter, f.sampling.filter);
    EXPECT_EQ(back.sampling.seed, f.sampling.seed);
    EXPECT_EQ(back.tracing.maxDepth, f.tracing.maxDepth);
    EXPECT_EQ(back.tracing.minWeight, f.tracing.minWeight);
  }
  for (const SamplePattern pattern :
       {SamplePattern::kRegular, SamplePattern::kJittered, SamplePattern::kAdaptive, SamplePattern::kPerceptual,
        SamplePattern::kSobol}) {
    FrameSettings f = someFrame();
    f.sampling.pattern = pattern;
    f.sampling.samples = 4;
    f.sampling.adaptiveThreshold = 0.125f;
    f.sampling.perceptualThreshold = 0.0625f;
    const FrameSettings back = decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28);
    EXPECT_EQ(back.sampling.pattern, pattern);
    if (pattern == SamplePattern::kAdaptive) {
      EXPECT_EQ(back.sampling.adaptiveThreshold, 0.125f);
    }
    if (pattern == SamplePattern::kPerceptual) {
      EXPECT_EQ(back.sampling.perceptualThreshold, 0.0625f);
    }
  }
  {  // the area lights' sample count travels, and is checked
    FrameSettings f = someFrame();
    f.sampling.lightSamples = 64;
    EXPECT_EQ(decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28).sampling.lightSamples,
              64);
    f.sampling.lightSamples = 5000;
    EXPECT_THROW(decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28), InputError);
  }
  {  // the output encoding travels
    FrameSettings f = someFrame();
    f.output = {Encoding::kSrgb, -1.5f};
    const FrameSettings back = decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28);
    EXPECT_EQ(back.output.encoding, Encoding::kSrgb);
    EXPECT_EQ(back.output.exposure, -1.5f);
    f.output.exposure = 99.0f;
    EXPECT_THROW(decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28), InputError);
  }
  {  // a threshold out of range is named
    FrameSettings f = someFrame();
    f.sampling.pattern = SamplePattern::kAdaptive;
    f.sampling.adaptiveThreshold = 0.0f;
    try {
      decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28);
      FAIL() << "took an adaptive threshold of 0";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("frame_setup.adaptive_threshold: must be in (0, 1]"), std::string::npos)
          << e.what();
    }
    f.sampling.pattern = SamplePattern::kPerceptual;
    f.sampling.adaptiveThreshold = 0.125f;
    f.sampling.perceptualThreshold = 2.0f;
    try {
      decodeFrameSettings(*decode(encodeFrameSetup(1, h, f)).body_as_FrameSetup(), 1 << 28);
      FAIL() << "took a perceptual threshold of 2";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("frame_setup.perceptual_threshold: must be in (0, 1]"), std::string::npos)
          << e.what();
    }
  }
}

TEST(Messages, TileRequestAndResultRoundTrip) {
  {
    const TileRect rect{16, 32, 10, 5};
    std::vector<std::uint8_t> mask(maskByteCount(rect), 0x5a);
    const auto* m = decode(encodeTileRequest(3, 44, rect, mask)).body_as_TileRequest();
    const TileRect back = decodeTileRect(*m, someFrame());
    EXPECT_EQ(back.x, 16);
    EXPECT_EQ(back.y, 32);
    EXPECT_EQ(back.width, 10);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(std::vector<std::uint8_t>(m->mask()->begin(), m->mask()->end()), mask);
  }
  {
    const std::vector<std::uint8_t> rgb = {1, 2, 3, 4, 5, 6};
    RayStats rays;
    rays.primary = 1000;
    rays.shadow = 900;
    rays.shadowBlocked = 80;
    rays.reflection = 70;
    rays.refraction = 60;
    rays.nonFiniteSamples = 1;
    rays.paths = 500;
    rays.longestPath = 7;
    rays.lightSamples = 1200;
    rays.pathBounces = 130;
    const auto* m = decode(encodeTileResult(3, 44, rgb, rays, 250)).body_as_TileResult();
    EXPECT_EQ(m->tile_id(), 44u);
    EXPECT_EQ(std::vector<std::uint8_t>(m->rgb()->begin(), m->rgb()->end()), rgb);
    const RayStats back = decodeRays(m->rays());
    EXPECT_EQ(back.primary, 1000u);
    EXPECT_EQ(back.shadow, 900u);
    EXPECT_EQ(back.shadowBlocked, 80u);
    EXPECT_EQ(back.reflection, 70u);
    EXPECT_EQ(back.refraction, 60u);
    EXPECT_EQ(back.nonFiniteSamples, 1u);
    EXPECT_EQ(back.paths, 500u);
    EXPECT_EQ(back.longestPath, 7u);
    EXPECT_EQ(back.pathBounces, 130u);
    EXPECT_EQ(back.lightSamples, 1200u);
    EXPECT_EQ(m->compute_us(), 250u);
  }
}

std::string problemOf(const std::function<void(FrameSettings&)>& edit) {
  FrameSettings f = someFrame();
  edit(f);
  const auto frame = encodeFrameSetup(1, someHash(), f);
  try {
    decodeFrameSettings(*decode(frame).body_as_FrameSetup(), 1 << 28);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Messages, BadFrameSettingsNameTheField) {
  EXPECT_NE(problemOf([](FrameSettings& f) { f.camera.eye.x = std::nanf(""); }).find("frame_setup.eye"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.camera.up = {0, 0, 0}; }).find("frame_setup.up"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.camera.fovY = 0; }).find("frame_setup.fov_y"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.width = 0; }).find("frame_setup.width"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.tracing.maxDepth = 0; }).find("frame_setup.max_depth"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.tracing.minWeight = std::nanf(""); }).find("min_weight"), std::string::npos);
  EXPECT_NE(problemOf([](FrameSettings& f) { f.sampling = {SamplePattern::kRegular, 3, FilterType::kBox, 0}; }).find("samples"), std::string::npos);
}

TEST(Messages, TilesOutsideTheImageOrWithWrongMasksAreRejected) {
  const FrameSettings f = someFrame();
  const auto check = [&](const TileRect& r, std::size_t maskBytes) {
    const std::vector<std::uint8_t> mask(maskBytes, 0xff);
    const auto frame = encodeTileRequest(1, 2, r, mask);
    EXPECT_THROW(decodeTileRect(*decode(frame).body_as_TileRequest(), f), InputError);
  };
  check({310, 0, 20, 10}, 0);
  check({0, 195, 10, 10}, 0);
  check({0, 0, 0, 10}, 0);
  check({0, 0, 8, 8}, 7);  // needs 8
}

TEST(Messages, BundleHashCoversTextFilesAndNames) {
  const SceneBundle a{"{}", {{"x", "1"}}};
  SceneBundle b = a;
  EXPECT_EQ(a.hash(), b.hash());
  b.files["x"] = "2";
  EXPECT_NE(a.hash(), b.hash());
  SceneBundle c{"{}", {{"y", "1"}}};
  EXPECT_NE(a.hash(), c.hash());
  SceneBundle d{"{} ", {{"x", "1"}}};
  EXPECT_NE(a.hash(), d.hash());
  EXPECT_EQ(toHex(SceneBundle{"", {}}.hash()), "af5570f5a1810b7af78caf4bc70a660f0df51e42baf91d4de5b2328de0e83dfc");
}

TEST(Messages, BundleOfTheBunnySceneCarriesItsMesh) {
  const LoadedBundle loaded = loadSceneBundle(test::sourcePath("scenes/bunny.json"));
  ASSERT_EQ(loaded.bundle.files.size(), 1u);
  EXPECT_TRUE(loaded.bundle.files.count("models/bunny.obj"));
  SceneBudget budget;
  const Scene again = loadBundle(loaded.bundle, budget);
  EXPECT_EQ(again.geometry.triangles().size(), loaded.scene.geometry.triangles().size());
}

// Every kind has a name in errors, one this build does not know its number.
TEST(Messages, BodyNamesNameUnknownKindsByNumber) {
  EXPECT_EQ(bodyName(wire::Body::Hello), "Hello");
  EXPECT_EQ(bodyName(static_cast<wire::Body>(200)), "type 200");
}

}  // namespace
}  // namespace glint::proto
