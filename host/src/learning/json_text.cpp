#include "json_text.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cstring>
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

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::size_t skipSpace(const std::string& text, std::size_t pos) {
  while (pos < text.size() && isSpace(text[pos])) ++pos;
  return pos;
}

// At an opening quote: the offset just after the closing one.
std::size_t stringEnd(const std::string& text, std::size_t pos) {
  for (++pos; pos < text.size(); ++pos) {
    if (text[pos] == '\\') {
      ++pos;  // the escaped character cannot close the string
    } else if (text[pos] == '"') {
      return pos + 1;
    }
  }
  return text.size();
}

// The string between begin and end (quotes included), with escapes decoded so
// that "we\u0069ghts" matches the key nlohmann saw.
std::string decodeString(const std::string& text, std::size_t begin, std::size_t end) {
  const std::string raw = text.substr(begin, end - begin);
  if (raw.find('\\') == std::string::npos) return raw.substr(1, raw.size() - 2);
  return nlohmann::json::parse(raw).get<std::string>();
}

// At a scalar: the offset just after it.
std::size_t scalarEnd(const std::string& text, std::size_t pos) {
  while (pos < text.size() && !isSpace(text[pos]) && !std::strchr(",]}", text[pos])) ++pos;
  return pos;
}

// At a value's first character: the offset just after the value. Counts
// brackets instead of recursing, so deep nesting cannot exhaust the stack.
std::size_t valueEnd(const std::string& text, std::size_t pos) {
  if (pos >= text.size()) return pos;
  if (text[pos] == '"') return stringEnd(text, pos);
  if (text[pos] != '{' && text[pos] != '[') return scalarEnd(text, pos);
  int depth = 0;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == '"') {
      pos = stringEnd(text, pos);
      continue;
    }
    if (c == '{' || c == '[') ++depth;
    if ((c == '}' || c == ']') && --depth == 0) return pos + 1;
    ++pos;
  }
  return pos;
}

// Past a ',' (and the spaces around it) if one is next.
std::size_t skipComma(const std::string& text, std::size_t pos) {
  pos = skipSpace(text, pos);
  if (pos < text.size() && text[pos] == ',') pos = skipSpace(text, pos + 1);
  return pos;
}

}  // namespace

std::size_t offsetOf(const std::string& text, const JsonPath& path) {
  const std::size_t start = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // a UTF-8 byte order mark, which nlohmann skips
  std::size_t pos = skipSpace(text, start);  // at the current value
  std::size_t found = pos;               // where the deepest step found is written
  for (const JsonPath::Step& step : path.steps()) {
    if (pos >= text.size()) return found;
    if (step.is_index) {
      if (text[pos] != '[') return found;
      pos = skipSpace(text, pos + 1);
      for (std::size_t i = 0;; ++i) {
        if (pos >= text.size() || text[pos] == ']') return found;
        if (i == step.index) break;
        pos = skipComma(text, valueEnd(text, pos));
      }
      found = pos;
    } else {
      if (text[pos] != '{') return found;
      pos = skipSpace(text, pos + 1);
      for (;;) {
        if (pos >= text.size() || text[pos] != '"') return found;
        const std::size_t key_begin = pos;
        const std::size_t key_end = stringEnd(text, pos);
        pos = skipSpace(text, key_end);
        pos = skipSpace(text, pos + 1);  // past ':'
        if (decodeString(text, key_begin, key_end) == step.key) {
          found = key_begin;
          break;
        }
        pos = skipComma(text, valueEnd(text, pos));
      }
    }
  }
  return found;
}

std::optional<DuplicateKey> findDuplicateKey(const std::string& text) {
  // One frame per open object or array; `step` is the member or element being
  // read, so the frames spell the path to the current value.
  struct Frame {
    bool object = false;
    bool expect_key = false;
    std::size_t count = 0;
    JsonPath::Step step;
    std::map<std::string, std::size_t> keys;  // key -> offset
  };
  std::vector<Frame> stack;
  auto pathHere = [&stack](const std::string& key) {
    JsonPath path;
    for (std::size_t i = 0; i + 1 < stack.size(); ++i) {
      const JsonPath::Step& s = stack[i].step;
      path = s.is_index ? path.index(s.index) : path.key(s.key);
    }
    return path.key(key);
  };
  // A value starts: in an array it is the next element.
  auto valueStarts = [&stack]() {
    if (!stack.empty() && !stack.back().object) stack.back().step = {true, {}, stack.back().count++};
  };

  std::size_t pos = 0;
  while ((pos = skipSpace(text, pos)) < text.size()) {
    const char c = text[pos];
    if (c == '{' || c == '[') {
      valueStarts();
      stack.push_back({c == '{', c == '{', 0, {}, {}});
      ++pos;
    } else if (c == '}' || c == ']') {
      if (!stack.empty()) stack.pop_back();
      ++pos;
    } else if (c == ',') {
      if (!stack.empty() && stack.back().object) stack.back().expect_key = true;
      ++pos;
    } else if (c == ':') {
      ++pos;
    } else if (c == '"') {
      const std::size_t end = stringEnd(text, pos);
      if (!stack.empty() && stack.back().expect_key) {
        Frame& frame = stack.back();
        frame.expect_key = false;
        std::string key = decodeString(text, pos, end);
        const auto [it, inserted] = frame.keys.emplace(key, pos);
        if (!inserted) return DuplicateKey{pathHere(key), it->second, pos};
        frame.step = {false, std::move(key), 0};
      } else {
        valueStarts();
      }
      pos = end;
    } else {
      valueStarts();
      pos = scalarEnd(text, pos);
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> findOverflowingNumber(const std::string& text) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == '"') {
      pos = stringEnd(text, pos);
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t end = scalarEnd(text, pos);
      // from_chars flags overflow and underflow alike; nlohmann refuses only
      // overflow (it reads 1e-400 as 0), so ask it about the rare out-of-range token.
      double value = 0;
      const auto result = std::from_chars(text.data() + pos, text.data() + end, value);
      if (result.ec == std::errc::result_out_of_range && !nlohmann::json::accept(text.substr(pos, end - pos))) {
        return pos;
      }
      pos = end;
    } else {
      ++pos;
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> findNestingBeyond(const std::string& text, int max_depth) {
  int depth = 0;
  for (std::size_t pos = 0; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (c == '"') {
      pos = stringEnd(text, pos) - 1;
    } else if (c == '{' || c == '[') {
      if (++depth > max_depth) return pos;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return std::nullopt;
}

}  // namespace pronk::policy_file
