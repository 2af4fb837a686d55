// Where things are written in a JSON text, for file:line messages. nlohmann
// parses values but keeps no positions, so on an error we walk the text again
// to the offending key. The walker assumes text that nlohmann has already
// parsed without a syntax error.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace pronk::policy_file {

// A path into a JSON document: keys and array indices, shown as
// "layers[1].weights[3][0]".
class JsonPath {
 public:
  struct Step {
    bool is_index = false;
    std::string key;
    std::size_t index = 0;
  };

  JsonPath key(const std::string& name) const;
  JsonPath index(std::size_t i) const;
  const std::vector<Step>& steps() const { return steps_; }
  std::string str() const;  // "" for the whole document

 private:
  std::vector<Step> steps_;
};

struct TextPosition {
  int line = 1;
  int column = 1;
};

// Line and column (1-based) of the character at a 0-based byte offset; an
// offset past the end is the position just after the last character.
TextPosition positionOf(const std::string& text, std::size_t offset);

// Byte offset where `path` is written: the key of an object member, the first
// character of an array element. A path that leads to nothing (a missing key,
// an index past the end) stops at the deepest part that exists.
std::size_t offsetOf(const std::string& text, const JsonPath& path);

// A key written twice in one object (nlohmann keeps only the last).
struct DuplicateKey {
  JsonPath path;           // the object's path plus the key
  std::size_t first = 0;   // offsets of the two keys
  std::size_t second = 0;
};
std::optional<DuplicateKey> findDuplicateKey(const std::string& text);

// Offset of the first number too large for a double (nlohmann reports those
// without a position). Scans numbers outside strings.
std::optional<std::size_t> findOverflowingNumber(const std::string& text);

// Offset of the first '{' or '[' (outside strings) that opens a level deeper
// than `max_depth`: nesting beyond it is refused before parsing, because the
// copies and destructors of a parsed document recurse once per level.
std::optional<std::size_t> findNestingBeyond(const std::string& text, int max_depth);

}  // namespace pronk::policy_file
