// The learning toolkit's random numbers: a seeded generator whose every output
// is fixed by this file, so that a training run is the same for a seed on
// every machine and standard library (std::normal_distribution and the other
// <random> distributions are not: their algorithms are left to the library).
#pragma once

#include <array>
#include <cstdint>

namespace pronk {

// xoshiro256** (Blackman and Vigna), seeded through SplitMix64; normals by
// Box-Muller. Its whole state is four words, which checkpoints store.
class Rng {
 public:
  using State = std::array<std::uint64_t, 4>;

  explicit Rng(std::uint64_t seed);

  std::uint64_t next();
  // Uniform on [0, 1), 53 random bits.
  double uniform();
  // Standard normal, one per call (the pair's sine half is dropped, so the
  // state stays four words).
  double normal();
  // Uniform integer in [0, n), n > 0, without modulo bias.
  std::uint64_t below(std::uint64_t n);

  const State& state() const { return state_; }
  void setState(const State& state);  // not all zero

 private:
  State state_;
};

}  // namespace pronk
