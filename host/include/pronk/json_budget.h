// What a JSON text may take in memory once read: one rule for every reader of
// policy files and checkpoints. A file of numbers takes about its own size as a
// document, but "[[],[],...]" takes 30 times its size; a reader spends the
// budget value by value as it parses and refuses the text once it runs out,
// before the document is built. Header-only: nothing but the standard library.
#pragma once

#include <cstddef>
#include <string>

namespace pronk {

class JsonMemoryBudget {
 public:
  // What the document and a reader's index hold per value, with the
  // allocator's overhead: a scalar; an object or array; an object's member.
  static constexpr std::size_t kScalarBytes = 32, kContainerBytes = 160, kKeyBytes = 96;
  static constexpr std::size_t kPerTextByte = 4;

  explicit JsonMemoryBudget(std::size_t text_bytes) : limit_(kPerTextByte * text_bytes + (std::size_t(1) << 20)) {}

  // False once the text has taken more than its budget.
  bool spend(std::size_t bytes) {
    used_ += bytes;
    return used_ <= limit_;
  }
  // "holds more values than its size allows: reading it would take more than N MiB"
  std::string refusal() const {
    return "holds more values than its size allows: reading it would take more than " +
           std::to_string(limit_ >> 20) + " MiB";
  }

 private:
  std::size_t limit_;
  std::size_t used_ = 0;
};

}  // namespace pronk
