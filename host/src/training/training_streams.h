// The seeds of a training run's random-number streams, derived from the
// file's seeds so that no two streams coincide: the constants differ in their
// high 32 bits, the seeds (< 2^32) only in the low ones.
#pragma once

#include <cstdint>

namespace pronk::training_streams {

inline std::uint64_t targetSeed(std::uint64_t seed) { return seed ^ 0x7461726765747300ull; }      // "targets"
inline std::uint64_t noiseSeed(std::uint64_t seed) { return seed ^ 0x6e6f697365000000ull; }       // "noise"
inline std::uint64_t validationSeed(std::uint64_t seed) { return seed ^ 0x76616c6964000000ull; }  // "valid"
// The learner (network initialisation, minibatch shuffles) takes the seed itself.

}  // namespace pronk::training_streams
