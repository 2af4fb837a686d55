#include "json_text.h"

#include "pronk/json_budget.h"

#include <nlohmann/json.hpp>

#include <iterator>
#include <string_view>
#include <map>

namespace pronk::policy_file {

JsonPath JsonPath::key(const std::string& name) const {
  JsonPath child = *this;
  child.steps_.push_back({false, name, 0});
  return child;
}

JsonPath JsonPath::index(std::size_t i) const {
  JsonPath child = *this;
  child.steps_.push_back({true, {}, i});
  return child;
}

std::string JsonPath::str() const {
  std::string out;
  for (const Step& step : steps_) {
    if (step.is_index) {
      out += "[" + std::to_string(step.index) + "]";
    } else {
      if (!out.empty()) out += ".";
      out += step.key;
    }
  }
  return out;
}

TextPosition positionOf(const std::string& text, std::size_t offset) {
  TextPosition p;
  const std::size_t end = std::min(offset, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else {
      ++p.column;
    }
  }
  return p;
}

std::string nlohmannDetail(const std::string& what) {
  std::string detail = what;
  if (const std::size_t end = detail.find("] "); detail.rfind('[', 0) == 0 && end != std::string::npos) {
    detail = detail.substr(end + 2);
  }
  if (const std::size_t colon = detail.find(": "); detail.rfind("parse error", 0) == 0 && colon != std::string::npos) {
    detail = detail.substr(colon + 2);
  }
  return detail;
}

// Where a value is written, and for an object or array the node of its insides.
struct Entry {
  std::size_t offset = 0;
  int node = -1;  // index into nodes_, -1 for a scalar
};

struct JsonLayout::Node {
  std::map<std::string, Entry> members;
  std::vector<Entry> elements;
};

namespace {

// A character iterator that publishes how far nlohmann's lexer has read. The
// lexer reads strictly forward and calls the SAX handler right after the
// token of the event, so at an event `*read` is just past that token (past
// one more character after a number, which the lexer reads and puts back).
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* at = nullptr;
  const char** read = nullptr;

  reference operator*() const { return *at; }
  CountingIterator& operator++() {
    *read = ++at;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingIterator& o) const { return at == o.at; }
  bool operator!=(const CountingIterator& o) const { return at != o.at; }
};

}  // namespace

class JsonLayout::Reader : public nlohmann::json_sax<nlohmann::json> {
 public:
  Reader(JsonLayout& layout, const char* begin, int max_depth, std::size_t text_bytes)
      : layout_(layout), begin_(begin), max_depth_(max_depth), budget_(text_bytes) {
    read_ = begin;
  }
  const char** cursor() { return &read_; }

  bool null() override { return scalar(); }
  bool boolean(bool) override { return scalar(); }
  bool number_integer(number_integer_t) override { return scalar(); }
  bool number_unsigned(number_unsigned_t) override { return scalar(); }
  bool number_float(number_float_t, const string_t&) override { return scalar(); }
  bool string(string_t&) override { return scalar(); }
  bool binary(binary_t&) override { return scalar(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& name) override {
    if (!spend(JsonMemoryBudget::kKeyBytes + name.size())) return false;
    Frame& frame = stack_.back();
    const std::size_t at = lastRead();
    auto& members = layout_.nodes_[frame.node].members;
    if (const auto it = members.find(name); it != members.end()) {
      if (!layout_.duplicate_) layout_.duplicate_ = DuplicateKey{pathTo(name), it->second.offset, at};
    }
    members[name] = Entry{at, -1};  // the last one counts, as in nlohmann's document
    frame.key = name;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token, const nlohmann::detail::exception& ex) override {
    Refusal r;
    r.message = nlohmannDetail(ex.what());
    if (ex.id == 406) {  // a number beyond a double: point at its first character, the token's last writing
      const std::string_view read(begin_, std::size_t(read_ - begin_));
      const std::size_t at = last_token.empty() ? std::string_view::npos : read.rfind(last_token);
      r.kind = Refusal::Kind::Overflow;
      r.offset = at == std::string_view::npos ? lastRead() : at;
    } else {  // the position counts from 1 and is the last character read: the culprit
      r.offset = position > 0 ? position - 1 : 0;
    }
    layout_.refusal_ = std::move(r);
    return false;
  }

 private:
  struct Frame {
    int node = 0;
    bool object = false;
    std::string key;  // the member being read, in an object
  };

  std::size_t lastRead() const { return read_ > begin_ ? std::size_t(read_ - begin_) - 1 : 0; }

  JsonPath pathTo(const std::string& key) const {
    JsonPath path;
    for (std::size_t i = 0; i + 1 < stack_.size(); ++i) {
      const Frame& f = stack_[i];
      path = f.object ? path.key(f.key) : path.index(layout_.nodes_[f.node].elements.size() - 1);
    }
    return path.key(key);
  }

  // Where the value that starts now goes: the document, a member, the next element.
  Entry& place(std::size_t at) {
    if (stack_.empty()) {
      layout_.document_ = at;
      return root_;
    }
    Frame& frame = stack_.back();
    Node& node = layout_.nodes_[frame.node];
    if (frame.object) return node.members[frame.key];  // the key's offset stays
    node.elements.push_back(Entry{at, -1});
    return node.elements.back();
  }

  bool spend(std::size_t bytes) {
    if (budget_.spend(bytes)) return true;
    layout_.refusal_ = Refusal{Refusal::Kind::TooLarge, lastRead(), budget_.refusal()};
    return false;
  }

  bool scalar() {
    if (!spend(JsonMemoryBudget::kScalarBytes)) return false;
    place(lastRead());
    return true;
  }

  bool open(bool object) {
    if (!spend(JsonMemoryBudget::kContainerBytes)) return false;
    const std::size_t at = lastRead();  // the bracket
    if (int(stack_.size()) >= max_depth_) {
      layout_.refusal_ = Refusal{Refusal::Kind::TooDeep, at, "nested more than " + std::to_string(max_depth_) +
                                                                 " levels deep"};
      return false;
    }
    const int index = int(layout_.nodes_.size());
    place(at).node = index;  // the document's own node is nodes_[0]
    layout_.nodes_.emplace_back();
    stack_.push_back(Frame{index, object, {}});
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

 private:
  JsonLayout& layout_;
  const char* begin_;
  const char* read_;
  int max_depth_;
  JsonMemoryBudget budget_;
  std::vector<Frame> stack_;
  Entry root_;  // the document's value: a scalar, or nodes_[0]
};

JsonLayout::JsonLayout(const std::string& text, int max_depth) {
  Reader reader(*this, text.data(), max_depth, text.size());
  const CountingIterator first{text.data(), reader.cursor()};
  const CountingIterator last{text.data() + text.size(), reader.cursor()};
  nlohmann::json::sax_parse(first, last, &reader);
}

JsonLayout::~JsonLayout() = default;
JsonLayout::JsonLayout(JsonLayout&&) noexcept = default;

std::size_t JsonLayout::offsetOf(const JsonPath& path) const {
  std::size_t found = document_;
  int node = nodes_.empty() ? -1 : 0;
  for (const JsonPath::Step& step : path.steps()) {
    if (node < 0) return found;
    const Node& n = nodes_[node];
    const Entry* entry = nullptr;
    if (step.is_index) {
      if (step.index < n.elements.size()) entry = &n.elements[step.index];
    } else if (const auto it = n.members.find(step.key); it != n.members.end()) {
      entry = &it->second;
    }
    if (!entry) return found;
    found = entry->offset;
    node = entry->node;
  }
  return found;
}

}  // namespace pronk::policy_file
