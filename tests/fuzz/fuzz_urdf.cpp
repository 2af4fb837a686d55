// libFuzzer target: the bytes as a URDF -> pronk::parseUrdf (the step of
// loadUrdf after reading the file: tinyxml2 pass, number checks, urdfdom, the
// body and joint tree). The origin sits beside the shipped Go1 so that
// relative mesh URIs resolve as they do for the real robot. A pronk::Error is
// the expected refusal; any other exception escapes and counts as a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "pronk/error.h"
#include "pronk/robot_description.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    pronk::parseUrdf(xml, PRONK_SOURCE_DIR "/assets/robots/go1/fuzz-input.urdf");
  } catch (const pronk::Error&) {
  }
  return 0;
}
