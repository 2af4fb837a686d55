#include "element_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace pronk::scenario_file {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string quoted(const char* text) { return std::string("\"") + text + "\""; }

}  // namespace

std::string formatNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

bool Range::contains(double v) const {
  const bool above_lo = lo_open ? v > lo : v >= lo;
  const bool below_hi = hi_open ? v < hi : v <= hi;
  return above_lo && below_hi;
}

std::string Range::describe(double scale) const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return std::string("in ") + (lo_open ? "(" : "[") + formatNumber(lo * scale) + ", " +
           formatNumber(hi * scale) + (hi_open ? ")" : "]");
  }
  if (has_lo) return std::string(lo_open ? "> " : ">= ") + formatNumber(lo * scale);
  if (has_hi) return std::string(hi_open ? "< " : "<= ") + formatNumber(hi * scale);
  return "finite";
}

SourceLocation locationOf(const tinyxml2::XMLNode& node, const SourceFile& file) {
  return SourceLocation{file.shown, node.GetLineNum()};
}

void failAt(const tinyxml2::XMLElement& element, const SourceFile& file, const std::string& message) {
  throw InputError(locationOf(element, file), "<" + std::string(element.Name()) + ">: " + message);
}

ElementReader::ElementReader(const tinyxml2::XMLElement& element, const SourceFile& file)
    : element_(element), file_(file) {}

SourceLocation ElementReader::where() const { return locationOf(element_, file_); }

std::string ElementReader::tag() const { return "<" + std::string(element_.Name()) + ">"; }

void ElementReader::fail(const std::string& message) const { failAt(element_, file_, message); }

bool ElementReader::has(const char* name) const { return element_.Attribute(name) != nullptr; }

const char* ElementReader::raw(const char* name) {
  if (std::find(known_.begin(), known_.end(), name) == known_.end()) known_.emplace_back(name);
  return element_.Attribute(name);
}

std::string ElementReader::text(const char* name, const std::string& fallback) {
  const char* value = raw(name);
  return value ? std::string(value) : fallback;
}

std::string ElementReader::requiredText(const char* name) {
  const char* value = raw(name);
  if (!value) fail("missing attribute " + std::string(name));
  if (*value == '\0') fail("attribute " + std::string(name) + " must not be empty");
  return value;
}

std::optional<std::string> ElementReader::optionalText(const char* name) {
  const char* value = raw(name);
  if (!value) return std::nullopt;
  return std::string(value);
}

bool ElementReader::boolean(const char* name, bool fallback) {
  const char* value = raw(name);
  if (!value) return fallback;
  if (std::strcmp(value, "true") == 0) return true;
  if (std::strcmp(value, "false") == 0) return false;
  fail(std::string(name) + "=" + quoted(value) + " must be true or false");
}

double ElementReader::parseNumber(const char* name, const char* text, const std::string& what) const {
  const char* begin = text;
  const char* end = text + std::strlen(text);
  while (begin < end && isSpace(*begin)) ++begin;
  while (end > begin && isSpace(end[-1])) --end;
  if (begin < end && *begin == '+') ++begin;  // from_chars takes no '+'
  double value = 0;
  const auto [stop, error] = std::from_chars(begin, end, value, std::chars_format::general);
  if (begin == end || error != std::errc() || stop != end || !std::isfinite(value)) {
    fail(std::string(name) + ": " + quoted(what.c_str()) + " is not a finite number");
  }
  return value;
}

void ElementReader::checkRange(const char* name, double value, const Range& range, double scale,
                               const char* unit) const {
  if (range.contains(value)) return;
  std::string suffix = unit && *unit ? std::string(" ") + unit : "";
  fail(std::string(name) + " must be " + range.describe(scale) + suffix + " (got " + formatNumber(value * scale) +
       ")");
}

std::vector<double> ElementReader::parseList(const char* name, const char* text) const {
  std::vector<double> values;
  const char* p = text;
  while (*p) {
    while (*p && isSpace(*p)) ++p;
    const char* start = p;
    while (*p && !isSpace(*p)) ++p;
    if (p > start) values.push_back(parseNumber(name, std::string(start, p).c_str(), std::string(start, p)));
  }
  return values;
}

double ElementReader::number(const char* name, double fallback, const Range& range) {
  const auto value = optionalNumber(name, range);
  return value ? *value : fallback;
}

double ElementReader::requiredNumber(const char* name, const Range& range) {
  const auto value = optionalNumber(name, range);
  if (!value) fail("missing attribute " + std::string(name));
  return *value;
}

std::optional<double> ElementReader::optionalNumber(const char* name, const Range& range) {
  const char* value = raw(name);
  if (!value) return std::nullopt;
  const double v = parseNumber(name, value, value);
  checkRange(name, v, range, 1, nullptr);
  return v;
}

Vec3 ElementReader::vec3(const char* name, const Vec3& fallback, const Range& each) {
  const char* value = raw(name);
  if (!value) return fallback;
  const std::vector<double> list = parseList(name, value);
  if (list.size() != 3) {
    fail(std::string(name) + " needs exactly 3 numbers, got " + std::to_string(list.size()) + " (" + quoted(value) +
         ")");
  }
  for (double v : list) checkRange(name, v, each, 1, nullptr);
  return {list[0], list[1], list[2]};
}

std::vector<double> ElementReader::numbers(const char* name, const Range& each) {
  const char* value = raw(name);
  if (!value) return {};
  std::vector<double> list = parseList(name, value);
  if (list.empty()) fail(std::string(name) + " needs at least one number");
  for (double v : list) checkRange(name, v, each, 1, nullptr);
  return list;
}

std::int64_t ElementReader::integer(const char* name, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
  const char* value = raw(name);
  if (!value) return fallback;
  // Padding allowed, as around every number of the format (XML Schema's
  // whitespace collapse for numbers).
  const char* begin = value;
  const char* end = value + std::strlen(value);
  while (begin < end && isSpace(*begin)) ++begin;
  while (end > begin && isSpace(end[-1])) --end;
  if (begin < end && *begin == '+') ++begin;
  std::int64_t v = 0;
  const auto [stop, error] = std::from_chars(begin, end, v);
  if (begin == end || error != std::errc() || stop != end) {
    fail(std::string(name) + ": " + quoted(value) + " is not an integer");
  }
  if (v < lo || v > hi) {
    fail(std::string(name) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
         std::to_string(v) + ")");
  }
  return v;
}

double ElementReader::angleScale() const { return file_.angle == AngleUnit::Deg ? kPi / 180 : 1.0; }

const char* ElementReader::angleUnitName() const { return file_.angle == AngleUnit::Deg ? "deg" : "rad"; }

double ElementReader::angle(const char* name, double fallback_rad, const Range& range) {
  const auto value = optionalAngle(name, range);
  return value ? *value : fallback_rad;
}

std::optional<double> ElementReader::optionalAngle(const char* name, const Range& range) {
  const char* value = raw(name);
  if (!value) return std::nullopt;
  const double v = parseNumber(name, value, value) * angleScale();
  checkRange(name, v, range, 1 / angleScale(), angleUnitName());
  return v;
}

double ElementReader::requiredAngle(const char* name, const Range& range) {
  const auto value = optionalAngle(name, range);
  if (!value) fail("missing attribute " + std::string(name));
  return *value;
}

std::vector<double> ElementReader::angles(const char* name, const Range& each) {
  const char* value = raw(name);
  if (!value) return {};
  std::vector<double> list = parseList(name, value);
  if (list.empty()) fail(std::string(name) + " needs at least one number");
  for (double& v : list) {
    v *= angleScale();
    checkRange(name, v, each, 1 / angleScale(), angleUnitName());
  }
  return list;
}

std::string ElementReader::path(const char* name, const std::string& fallback) {
  const char* value = raw(name);
  if (!value) return fallback;
  if (*value == '\0') fail("attribute " + std::string(name) + " must not be empty");
  return (file_.directory / value).lexically_normal().string();
}

void ElementReader::requireFile(const std::string& path, const std::string& what, bool directory) const {
  // The error_code overload: the throwing one let std::filesystem_error out of
  // the reader for a name over 255 bytes (found by fuzzing).
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (directory ? std::filesystem::is_directory(status) : std::filesystem::is_regular_file(status)) return;
  const bool refused = ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory;
  fail(what + " not found: " + path + (refused ? " (" + ec.message() + ")" : ""));
}

void ElementReader::rejectUnknownAttributes() const {
  for (const tinyxml2::XMLAttribute* a = element_.FirstAttribute(); a; a = a->Next()) {
    if (std::find(known_.begin(), known_.end(), a->Name()) != known_.end()) continue;
    std::string list;
    for (const std::string& k : known_) list += (list.empty() ? "" : ", ") + k;
    fail("unknown attribute \"" + std::string(a->Name()) + "\"" +
         (list.empty() ? std::string(" (it takes none)") : " (known: " + list + ")"));
  }
}

std::vector<const tinyxml2::XMLElement*> ElementReader::children(std::initializer_list<const char*> allowed) const {
  std::vector<const tinyxml2::XMLElement*> kids;
  for (const tinyxml2::XMLNode* node = element_.FirstChild(); node; node = node->NextSibling()) {
    if (const tinyxml2::XMLText* t = node->ToText()) {
      const std::string s = t->Value();
      if (std::all_of(s.begin(), s.end(), isSpace)) continue;
      throw InputError(locationOf(*node, file_), tag() + ": unexpected text \"" + s.substr(0, 40) +
                                                     "\" (values go in attributes)");
    }
    const tinyxml2::XMLElement* child = node->ToElement();
    if (!child) continue;  // comments, processing instructions
    const bool known = std::any_of(allowed.begin(), allowed.end(),
                                   [&](const char* a) { return std::strcmp(a, child->Name()) == 0; });
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      failAt(*child, file_,
             "unknown element in " + tag() +
                 (list.empty() ? std::string(" (it takes no children)") : " (allowed: " + list + ")"));
    }
    kids.push_back(child);
  }
  return kids;
}

void ElementReader::rejectRepeated(const std::vector<const tinyxml2::XMLElement*>& kids, const char* name) const {
  const tinyxml2::XMLElement* first = nullptr;
  for (const tinyxml2::XMLElement* k : kids) {
    if (std::strcmp(k->Name(), name) != 0) continue;
    if (first) failAt(*k, file_, "duplicate in " + tag() + " (the first is at line " +
                                     std::to_string(first->GetLineNum()) + ")");
    first = k;
  }
}

}  // namespace pronk::scenario_file
