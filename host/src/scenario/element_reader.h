// Reading one XML element of a scenario file: typed attributes parsed strictly,
// range checks with messages that name the attribute and the allowed range,
// and a record of which attributes were read so that the rest are reported as
// unknown. Every error is an InputError at the element's file and line.
#pragma once

#include <tinyxml2.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pronk/error.h"
#include "pronk/scenario.h"

namespace pronk::scenario_file {

enum class AngleUnit { Rad, Deg };

// One XML file of a scenario (the top-level file or an included one).
struct SourceFile {
  std::string shown;                 // path as used in messages (as given, normalised)
  std::filesystem::path directory;   // absolute directory, for relative paths inside it
  AngleUnit angle = AngleUnit::Rad;  // the file's own angle="..." (default rad)
};

// The closed or open interval a number must lie in; bounds in SI units (rad
// for angles).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {0, Range{}.hi, true, false}; }
  static Range nonNegative() { return {0, Range{}.hi, false, false}; }
  static Range above(double x) { return {x, Range{}.hi, true, false}; }
  static Range atLeast(double x) { return {x, Range{}.hi, false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  bool contains(double v) const;
  // "> 0", ">= 0.2", "in [0, 1]", "in (-90, 90)", with bounds multiplied by scale.
  std::string describe(double scale = 1) const;
};

// "%g"-style text of a number for messages.
std::string formatNumber(double v);

class ElementReader {
 public:
  ElementReader(const tinyxml2::XMLElement& element, const SourceFile& file);

  const tinyxml2::XMLElement& element() const { return element_; }
  const SourceFile& file() const { return file_; }
  SourceLocation where() const;
  // "<tag>" for messages.
  std::string tag() const;
  [[noreturn]] void fail(const std::string& message) const;

  bool has(const char* name) const;

  // Text attributes. requiredText refuses an absent or empty value.
  std::string text(const char* name, const std::string& fallback);
  std::string requiredText(const char* name);
  std::optional<std::string> optionalText(const char* name);  // may be empty
  // One of `choices` (any container of string_view-convertibles).
  template <class Choices>
  std::string choice(const char* name, const std::string& fallback, const Choices& choices);
  bool boolean(const char* name, bool fallback);

  // Numbers: finite decimal numbers, nothing else in the value.
  double number(const char* name, double fallback, const Range& range = Range::any());
  double requiredNumber(const char* name, const Range& range = Range::any());
  std::optional<double> optionalNumber(const char* name, const Range& range = Range::any());
  Vec3 vec3(const char* name, const Vec3& fallback, const Range& each = Range::any());
  // A whitespace-separated list of at least one number (absent: empty list).
  std::vector<double> numbers(const char* name, const Range& each = Range::any());
  std::int64_t integer(const char* name, std::int64_t fallback, std::int64_t lo, std::int64_t hi);

  // Angles are written in the file's unit and returned in rad; `range` is in rad
  // and described in the file's unit.
  double angle(const char* name, double fallback_rad, const Range& range = Range::any());
  std::optional<double> optionalAngle(const char* name, const Range& range = Range::any());
  double requiredAngle(const char* name, const Range& range = Range::any());
  std::vector<double> angles(const char* name, const Range& each = Range::any());
  double angleScale() const;       // file unit -> rad
  const char* angleUnitName() const;

  // A path relative to this file's directory (or absolute), made absolute.
  std::string path(const char* name, const std::string& fallback);
  // Fails "<what> not found: PATH" unless PATH is a regular file (a directory
  // with `directory`); a path the system refuses (a name over 255 bytes, a
  // folder that may not be entered) gets the system's reason in parentheses.
  void requireFile(const std::string& path, const std::string& what, bool directory = false) const;

  // Reports the first attribute that no accessor above asked for.
  void rejectUnknownAttributes() const;

  // The child elements, each of whose names must be in `allowed`; text that is
  // not whitespace is an error (comments are fine).
  std::vector<const tinyxml2::XMLElement*> children(std::initializer_list<const char*> allowed) const;
  // Fails at a child's line when a name occurs twice among `kids`.
  void rejectRepeated(const std::vector<const tinyxml2::XMLElement*>& kids, const char* name) const;

 private:
  const char* raw(const char* name);  // marks the name known; nullptr when absent
  double parseNumber(const char* name, const char* text, const std::string& what) const;
  void checkRange(const char* name, double value, const Range& range, double scale, const char* unit) const;
  std::vector<double> parseList(const char* name, const char* text) const;

  const tinyxml2::XMLElement& element_;
  const SourceFile& file_;
  std::vector<std::string> known_;
};

// Fails at `where` naming the element: "<tag> message".
[[noreturn]] void failAt(const tinyxml2::XMLElement& element, const SourceFile& file, const std::string& message);
SourceLocation locationOf(const tinyxml2::XMLNode& node, const SourceFile& file);

template <class Choices>
std::string ElementReader::choice(const char* name, const std::string& fallback, const Choices& choices) {
  const std::string value = text(name, fallback);
  std::string list;
  for (const auto& c : choices) {
    if (value == std::string_view(c)) return value;
    list += (list.empty() ? "" : ", ") + std::string(c);
  }
  fail(std::string(name) + "=\"" + value + "\" is not one of: " + list);
}

}  // namespace pronk::scenario_file
