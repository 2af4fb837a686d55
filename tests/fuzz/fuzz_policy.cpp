// libFuzzer target: the bytes as a policy file's text -> pronk::parsePolicy,
// which loadPolicy calls on the file it read (the read itself is
// readInputFile's: a regular file within a size bound). A pronk::Error is the
// expected refusal; any other exception escapes and counts as a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "pronk/error.h"
#include "pronk/policy.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const pronk::MlpPolicy policy = pronk::parsePolicy(text, "fuzz.json");
    // A policy that was accepted must write out and read back (the checksum
    // and the exact number printing are part of the format).
    pronk::parsePolicy(pronk::policyToJson(policy), "fuzz-rewritten.json");
  } catch (const pronk::Error&) {
  }
  return 0;
}
