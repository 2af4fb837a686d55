// One reader per top-level element of a scenario file. Each checks its own
// element's attributes, children and ranges; checks that need more than one
// element (URDF masses against trunk_mass_offset, sweep values against the
// contact) are in scenario_file.cpp.
#pragma once

#include <tinyxml2.h>

#include <string_view>

#include "element_reader.h"
#include "pronk/scenario.h"

namespace pronk::scenario_file {

PlatformSpec readPlatform(const tinyxml2::XMLElement& element, const SourceFile& file);
ControllerSpec readController(const tinyxml2::XMLElement& element, const SourceFile& file);
EnvironmentSpec readEnvironment(const tinyxml2::XMLElement& element, const SourceFile& file);
SimSpec readSim(const tinyxml2::XMLElement& element, const SourceFile& file);
// Fills scenario.ground, ground_height and terrain.
void readTerrain(const tinyxml2::XMLElement& element, const SourceFile& file, Scenario& scenario);
std::vector<TargetSpec> readTargets(const tinyxml2::XMLElement& element, const SourceFile& file);
std::vector<SweepSpec> readSweeps(const tinyxml2::XMLElement& element, const SourceFile& file);
RenderSpec readRender(const tinyxml2::XMLElement& element, const SourceFile& file);
TrainingSpec readTraining(const tinyxml2::XMLElement& element, const SourceFile& file);
std::vector<ExpectSpec> readExpectations(const tinyxml2::XMLElement& element, const SourceFile& file);
// The <param name=".." value=".."/> children of r's element (no other children),
// kept as text: the plugin's schema checks them.
std::vector<ParamSetting> readParams(ElementReader& r, const SourceFile& file);

// The element name a sweep's axes are written with: axis, uniform or vary.
const char* axisElementName(SweepSpec::Kind kind);

// Whitespace-separated words of a value.
std::vector<std::string> splitWords(std::string_view text);

// Target roll and pitch are limited to this open interval (rad).
constexpr double kMaxTiltRad = 1.57079632679489661923;

}  // namespace pronk::scenario_file
