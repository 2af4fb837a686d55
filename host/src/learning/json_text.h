// Where things are written in a JSON text, for file:line messages. nlohmann's
// documents keep no positions; its SAX parser, fed through an iterator that
// counts what the lexer has read, tells them.
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

// nlohmann's what() without its "[json.exception.parse_error.101] parse error
// at line 2, column 11: " prefix: pronk's messages say where themselves.
std::string nlohmannDetail(const std::string& what);

// What nlohmann's parsed document does not keep, from one pass of its SAX
// parser over the text: where each key and array element is written, the first
// key written twice in one object, and where and why the text is refused
// (a syntax error, a number beyond a double, nesting deeper than a bound).
// The SAX parser keeps its own stack, so a hostile depth cannot exhaust ours;
// the document's copies and destructors recurse, hence the bound. Memory is
// bounded too: a text whose document and layout would take more than its
// JsonMemoryBudget (pronk/json_budget.h) is refused (TooLarge) as soon as it
// gets there.
class JsonLayout {
 public:
  JsonLayout(const std::string& text, int max_depth);
  ~JsonLayout();
  JsonLayout(JsonLayout&&) noexcept;

  struct Refusal {
    enum class Kind { Syntax, Overflow, TooDeep, TooLarge } kind = Kind::Syntax;
    std::size_t offset = 0;  // the culprit: the character read last, the number, the bracket
    std::string message;     // nlohmann's, without its "[json.exception...] " prefix
  };
  // Set when the text is not a document nlohmann would parse whole; the
  // layout then holds what was read up to there.
  const std::optional<Refusal>& refusal() const { return refusal_; }

  // A key written twice in one object (nlohmann keeps only the last).
  struct DuplicateKey {
    JsonPath path;           // the object's path plus the key
    std::size_t first = 0;   // offsets of the two keys
    std::size_t second = 0;
  };
  const std::optional<DuplicateKey>& duplicateKey() const { return duplicate_; }

  // Offset where `path` is written: an object member's key, an array element.
  // A path that leads to nothing (a missing key, an index past the end) stops
  // at the deepest part that exists; the empty path is the document.
  std::size_t offsetOf(const JsonPath& path) const;

  struct Node;
  class Reader;

 private:
  std::vector<Node> nodes_;  // nodes_[0]: the document's, when it is an object or array
  std::size_t document_ = 0;  // where the document's value starts
  std::optional<Refusal> refusal_;
  std::optional<DuplicateKey> duplicate_;
};

}  // namespace pronk::policy_file
