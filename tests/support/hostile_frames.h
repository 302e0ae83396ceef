#pragma once

#include <cstdint>
#include <vector>

#include "proto/framing.h"

namespace glint::proto::test {

// A frame that passes flatbuffers::Verifier yet names a body type and carries
// no body table (28 bytes): the message that crashed glintd before Hello.
inline std::vector<std::uint8_t> bodylessFrame(wire::Body type) {
  flatbuffers::FlatBufferBuilder b;
  wire::MessageBuilder message(b);
  message.add_body_type(type);
  return finishFrame(b, message.Finish());
}

// Every body type a message can name.
inline std::vector<wire::Body> allBodyTypes() {
  std::vector<wire::Body> types;
  for (auto t = static_cast<int>(wire::Body::MIN) + 1; t <= static_cast<int>(wire::Body::MAX); ++t) {
    types.push_back(static_cast<wire::Body>(t));
  }
  return types;
}

}  // namespace glint::proto::test
