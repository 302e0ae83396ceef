// libFuzzer target: framing and message decoding. Any bytes go through the
// FrameReader both ends read with; every verified message goes through the decoder of its kind,
// which must either return checked values or throw InputError.
#include <cstddef>
#include <cstdint>

#include "common/base/error.h"
#include "proto/framing.h"
#include "proto/messages.h"
#include "tests/fuzz/fuzz_messages.h"

namespace {

using namespace glint;

void decodeBody(const wire::Message& m) {
  try {
    if (const auto* q = m.body_as_SceneQuery()) {
      (void)proto::decodeHash(q->hash(), "hash");
      (void)proto::decodeFileHashes(*q, proto::kMaxSceneFiles);
    }
    if (const auto* u = m.body_as_SceneUpload()) (void)proto::decodeManifest(*u);
    if (const auto* c = m.body_as_FileChunk()) {
      (void)proto::decodeHash32(c->hash(), "hash");
      if (c->data()) (void)c->data()->size();
    }
    if (const auto* s = m.body_as_FrameSetup()) {
      const FrameSettings frame = proto::decodeFrameSettings(*s, std::size_t{1} << 28);
      (void)frame;
    }
    if (const auto* t = m.body_as_TileRequest()) {
      FrameSettings frame;
      frame.width = 640;
      frame.height = 480;
      (void)proto::decodeTileRect(*t, frame);
    }
    if (const auto* r = m.body_as_TileResult()) {
      (void)proto::decodeRays(r->rays());
      if (r->rgb()) (void)r->rgb()->size();
    }
    if (const auto* e = m.body_as_Error()) {
      if (e->message()) (void)e->message()->str();
    }
    if (const auto* h = m.body_as_Hello()) {
      if (h->software()) (void)h->software()->str();
    }
  } catch (const InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::forEachMessage(data, size, decodeBody, [] { return true; });
  return 0;
}
