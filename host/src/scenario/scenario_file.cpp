// loadScenario: opens the top-level file, splices <include>d files in place,
// hands each top-level element to its section reader (sections.h), then runs
// the checks that span several elements.
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "element_reader.h"
#include "pronk/scenario.h"
#include "sections.h"
#include "pronk/file_io.h"
#include "urdf_root_mass.h"

namespace pronk {

namespace {

namespace fs = std::filesystem;
using scenario_file::AngleUnit;
using scenario_file::ElementReader;
using scenario_file::SourceFile;
using tinyxml2::XMLElement;

constexpr const char* kTopRoot = "scenario";
constexpr const char* kPartRoot = "scenario_part";

// tinyxml2's error, in words a user can act on.
std::string describeXmlError(const tinyxml2::XMLDocument& doc) {
  std::string what;
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: what = "malformed or repeated attribute"; break;
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: what = "element closed by the wrong end tag, or never closed"; break;
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: what = "malformed element"; break;
    case tinyxml2::XML_ERROR_PARSING_TEXT: what = "malformed text (a bare '<' or '&'?)"; break;
    case tinyxml2::XML_ERROR_PARSING_COMMENT: what = "unterminated comment"; break;
    case tinyxml2::XML_ERROR_PARSING_CDATA: what = "unterminated CDATA section"; break;
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: what = "malformed <?xml ...?> declaration"; break;
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: what = "the file holds no element"; break;
    default: what = doc.ErrorName(); break;
  }
  // ErrorStr() ends with ": <detail>", e.g. "XMLElement name=robot".
  const std::string full = doc.ErrorStr() ? doc.ErrorStr() : "";
  const size_t line_pos = full.find("Line number=");
  const size_t colon = line_pos == std::string::npos ? std::string::npos : full.find(": ", line_pos);
  if (colon != std::string::npos) {
    std::string detail = full.substr(colon + 2);
    const std::string element_prefix = "XMLElement name=";
    if (detail.rfind(element_prefix, 0) == 0) detail = "in <" + detail.substr(element_prefix.size()) + ">";
    if (!detail.empty()) what += " (" + detail + ")";
  }
  return "XML syntax error: " + what;
}

// "1", "1.0", "1.2": returns the major number, or -1 when malformed.
int majorVersion(const std::string& v) {
  size_t i = 0;
  int major = 0;
  while (i < v.size() && std::isdigit(static_cast<unsigned char>(v[i])) && major < 100000) {
    major = major * 10 + (v[i++] - '0');
  }
  if (i == 0) return -1;
  if (i == v.size()) return major;
  if (v[i] != '.' || i + 1 == v.size()) return -1;
  for (size_t j = i + 1; j < v.size(); ++j) {
    if (!std::isdigit(static_cast<unsigned char>(v[j]))) return -1;
  }
  return major;
}

class Loader {
 public:
  // `part`: the file is a <scenario_part> read on its own, to check it:
  // nothing is required of it.
  explicit Loader(bool part = false) : part_(part) {}
  Scenario load(const std::string& path);

 private:
  struct Item {
    const XMLElement* element;
    const SourceFile* file;
  };

  // Parses `shown` (a path usable from the working directory) and returns its root.
  const XMLElement& open(const fs::path& shown, SourceFile& file, const SourceLocation& missing_at);
  void readRoot(const XMLElement& root, SourceFile& file, bool top);
  void include(const XMLElement& element, const SourceFile& file);
  void dispatch(Scenario& scenario);
  // readEnvironment, then the <param>s of the <include>s that brought it in.
  EnvironmentSpec readOverriddenEnvironment(const XMLElement& element, const SourceFile& file) const;
  void checkAcrossElements(Scenario& scenario) const;

  std::vector<std::unique_ptr<tinyxml2::XMLDocument>> documents_;
  std::vector<std::unique_ptr<SourceFile>> files_;
  std::vector<fs::path> include_chain_;        // identities of the files being read
  std::vector<std::string> include_chain_shown_;
  std::vector<Item> items_;                    // top-level elements, includes spliced in
  // <param>s written inside an <include>, per included <environment>, inner includes first.
  std::map<const XMLElement*, std::vector<ParamSetting>> environment_overrides_;
  std::string scenario_name_;
  SourceLocation top_where_;
  bool part_ = false;
};

const XMLElement& Loader::open(const fs::path& shown, SourceFile& file, const SourceLocation& missing_at) {
  file.shown = shown.string();
  file.directory = fs::absolute(shown).lexically_normal().parent_path();
  auto doc = std::make_unique<tinyxml2::XMLDocument>();
  std::error_code ec;
  if (!fs::exists(shown, ec)) throw InputError(missing_at, "cannot open " + file.shown + ": no such file");
  try {
    checkInputFile(file.shown, "scenario file", 64ull << 20);
  } catch (const InputError& e) {
    throw InputError(missing_at, e.what());
  }
  if (doc->LoadFile(file.shown.c_str()) == tinyxml2::XML_ERROR_FILE_NOT_FOUND ||
      doc->ErrorID() == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED) {
    throw InputError(missing_at, "cannot open " + file.shown);
  }
  if (doc->Error()) throw InputError(SourceLocation{file.shown, doc->ErrorLineNum()}, describeXmlError(*doc));
  const XMLElement* root = doc->RootElement();
  if (!root) {
    // Only a comment or the XML declaration: tinyxml2 parses it, but there is nothing to read.
    throw InputError(SourceLocation{file.shown, 1},
                     "no root element: a scenario file holds one <scenario>, an included one one <scenario_part>");
  }
  if (const XMLElement* second = root->NextSiblingElement()) {
    scenario_file::failAt(*second, file, "a second root element; a file holds one <scenario> or <scenario_part>");
  }
  documents_.push_back(std::move(doc));
  return *root;
}

void Loader::readRoot(const XMLElement& root, SourceFile& file, bool top) {
  const char* expected = top && !part_ ? kTopRoot : kPartRoot;
  if (std::string(root.Name()) != expected) {
    scenario_file::failAt(root, file,
                          top ? "the root element must be <scenario> (a <scenario_part> is meant to be included)"
                              : "an included file's root element must be <scenario_part>");
  }
  ElementReader r(root, file);
  const std::string version = r.requiredText("version");
  const int major = majorVersion(version);
  if (major < 0) r.fail("version=\"" + version + "\" is not a format version such as \"1\" or \"1.0\"");
  if (major != kScenarioFormatVersion) {
    r.fail("format version " + version + " is not supported: this build reads version " +
           std::to_string(kScenarioFormatVersion));
  }
  const std::string unit = r.choice("angle", "rad", std::array<const char*, 2>{"rad", "deg"});
  file.angle = unit == "deg" ? AngleUnit::Deg : AngleUnit::Rad;
  if (top) {
    scenario_name_ = part_ ? fs::path(file.shown).stem().string() : r.text("name", fs::path(file.shown).stem().string());
    top_where_ = r.where();
  }
  r.rejectUnknownAttributes();
  const auto kids =
      r.children({"include", "platform", "controller", "environment", "sim", "terrain", "targets", "sweeps", "render",
                  "training", "expectations"});
  for (const XMLElement* k : kids) {
    if (std::string(k->Name()) == "include") {
      include(*k, file);
    } else {
      items_.push_back({k, &file});
    }
  }
}

void Loader::include(const XMLElement& element, const SourceFile& file) {
  ElementReader r(element, file);
  const std::string relative = r.requiredText("file");
  r.rejectUnknownAttributes();
  const std::vector<ParamSetting> overrides = scenario_file::readParams(r, file);
  const fs::path target = fs::path(relative).is_absolute()
                              ? fs::path(relative).lexically_normal()
                              : (fs::path(file.shown).parent_path() / relative).lexically_normal();
  r.requireFile(target.string(), "included file");
  std::error_code ec;
  fs::path identity = fs::weakly_canonical(target, ec);
  if (ec) identity = target;
  for (const fs::path& open_file : include_chain_) {
    if (open_file != identity) continue;
    std::string chain;
    for (const std::string& s : include_chain_shown_) chain += s + " -> ";
    r.fail("include cycle: " + chain + target.string());
  }
  files_.push_back(std::make_unique<SourceFile>());
  SourceFile& part = *files_.back();
  const XMLElement& root = open(target, part, r.where());
  include_chain_.push_back(identity);
  include_chain_shown_.push_back(part.shown);
  const size_t first_item = items_.size();
  readRoot(root, part, false);
  include_chain_.pop_back();
  include_chain_shown_.pop_back();
  if (overrides.empty()) return;
  // The <param>s override (or add to) those of the <environment> the included
  // file brings in, itself or through its own includes.
  const auto environment = std::find_if(items_.begin() + static_cast<std::ptrdiff_t>(first_item), items_.end(),
                                        [](const Item& item) { return std::string(item.element->Name()) == "environment"; });
  if (environment == items_.end()) {
    r.fail("<param> in an <include> sets a parameter of the included <environment>, but " + part.shown +
           " brings in no <environment>");
  }
  std::vector<ParamSetting>& applied = environment_overrides_[environment->element];
  applied.insert(applied.end(), overrides.begin(), overrides.end());
}

EnvironmentSpec Loader::readOverriddenEnvironment(const XMLElement& element, const SourceFile& file) const {
  EnvironmentSpec env = scenario_file::readEnvironment(element, file);
  const auto overrides = environment_overrides_.find(&element);
  if (overrides == environment_overrides_.end()) return env;
  for (const ParamSetting& setting : overrides->second) setParam(env.params, setting);
  return env;
}

void Loader::dispatch(Scenario& scenario) {
  std::map<std::string, Item> first;
  std::optional<ControllerSpec> scenario_controller;
  for (const Item& item : items_) {
    const XMLElement& e = *item.element;
    const SourceFile& f = *item.file;
    const std::string name = e.Name();
    const auto [it, inserted] = first.emplace(name, item);
    if (!inserted) {
      const SourceLocation earlier = scenario_file::locationOf(*it->second.element, *it->second.file);
      scenario_file::failAt(e, f, "a scenario holds one <" + name + ">; the first is at " + earlier.str());
    }
    if (name == "platform") scenario.platform = scenario_file::readPlatform(e, f);
    else if (name == "controller") scenario_controller = scenario_file::readController(e, f);
    else if (name == "environment") scenario.environment = readOverriddenEnvironment(e, f);
    else if (name == "sim") scenario.sim = scenario_file::readSim(e, f);
    else if (name == "terrain") scenario_file::readTerrain(e, f, scenario);
    else if (name == "targets") scenario.targets = scenario_file::readTargets(e, f);
    else if (name == "sweeps") scenario.sweeps = scenario_file::readSweeps(e, f);
    else if (name == "render") scenario.render = scenario_file::readRender(e, f);
    else if (name == "training") scenario.training = scenario_file::readTraining(e, f);
    else if (name == "expectations") scenario.expectations = scenario_file::readExpectations(e, f);
  }
  if (part_) {
    if (scenario_controller) scenario.platform.controller = *scenario_controller;
    return;
  }
  if (!first.count("platform")) {
    throw InputError(top_where_, "<scenario>: no <platform> (write one, or include a platform file)");
  }
  if (!first.count("sim")) {
    scenario.sim.where = SourceLocation{top_where_.file, 0};
    scenario.sim.contact.where = scenario.sim.where;
  }
  if (scenario_controller) scenario.platform.controller = *scenario_controller;
  if (scenario.platform.controller.factory.empty() && !scenario.environment) {
    throw InputError(scenario.platform.where,
                     "<platform>: no <controller> here or at the top level of the scenario (nor an <environment>)");
  }
}

// <training> trains a policy for the scenario's <environment>, and targets with
// heights stand on step platforms.
void checkTraining(const Scenario& scenario) {
  if (!scenario.training) return;
  const TrainingSpec& t = *scenario.training;
  if (!scenario.environment) {
    throw InputError(t.where, "<training>: needs an <environment> (the task the policy is trained on)");
  }
  const bool heights = t.z.min != 0 || t.z.max != 0;
  if (heights && scenario.step_platforms == StepPlatforms::none) {
    throw InputError(t.region_where, "<region>: z spans [" + scenario_file::formatNumber(t.z.min) + ", " +
                                         scenario_file::formatNumber(t.z.max) +
                                         "] m: targets with heights need <terrain step_platforms=\"true\"> or \"apex\"");
  }
  // A target with a height needs its platform's edge between start and target.
  const double far_x = std::max(std::abs(t.x.min), std::abs(t.x.max));
  const double far_y = std::max(std::abs(t.y.min), std::abs(t.y.max));
  if (heights && std::hypot(far_x, far_y) < 0.2) {
    throw InputError(t.region_where, "<region>: targets with heights must lie >= 0.1 m from the start (their step "
                                     "platform's edge goes between); this x, y box stays within 0.2 m of it");
  }
}

// Each <expect> names a set or a target the scenario has, and the jumps need an <environment>.
void checkExpectations(const Scenario& scenario) {
  for (const ExpectSpec& e : scenario.expectations) {
    if (!scenario.environment) {
      throw InputError(e.where, "<expect>: needs an <environment> (expectations are about its jumps)");
    }
    if (!e.target.empty()) {
      const bool known = std::any_of(scenario.targets.begin(), scenario.targets.end(),
                                     [&](const TargetSpec& t) { return t.name == e.target; });
      if (!known) throw InputError(e.where, "<expect>: target=\"" + e.target + "\" is not one of the <targets>");
      continue;
    }
    if (e.set == "targets") {
      if (scenario.targets.empty()) throw InputError(e.where, "<expect>: set=\"targets\" but the scenario has no <targets>");
      continue;
    }
    const bool found = std::any_of(scenario.sweeps.begin(), scenario.sweeps.end(),
                                   [&](const SweepSpec& sweep) { return sweep.name == e.set; });
    std::string known;
    for (const SweepSpec& sweep : scenario.sweeps) known += (known.empty() ? "" : ", ") + sweep.name;
    if (!found) {
      throw InputError(e.where, "<expect>: set=\"" + e.set + "\" is neither \"targets\" nor a sweep of the scenario" +
                                    (known.empty() ? std::string(" (it has none)") : " (" + known + ")"));
    }
  }
}

void Loader::checkAcrossElements(Scenario& scenario) const {
  if (!part_) checkTraining(scenario);  // a part on its own needs nothing else
  if (!part_) checkExpectations(scenario);
  const PlatformSpec& p = scenario.platform;
  const auto root = scenario_file::urdfRootBody(p.urdf);
  // The two offsets together: the simulated root body must keep a positive mass.
  // `both`: the unreported mass is part of the sum (named then, so that the message explains it).
  const auto massMessage = [&](double offset, bool both) {
    return std::string(both ? "trunk_mass_offset + unreported_trunk_mass" : "trunk_mass_offset") + " must be > " +
           scenario_file::formatNumber(-root->mass) +
           " kg: the root body of " + p.urdf + " (link " + root->link + " and the links fixed to it) weighs " +
           scenario_file::formatNumber(root->mass) + " kg (got " + scenario_file::formatNumber(offset) + ")";
  };
  if (root && p.trunk_mass_offset + p.unreported_trunk_mass <= -root->mass) {
    throw InputError(p.where, "<platform>: " + massMessage(p.trunk_mass_offset + p.unreported_trunk_mass,
                                                           p.unreported_trunk_mass != 0));
  }
  for (const SweepSpec& sweep : scenario.sweeps) {
    const std::string tag = std::string("<") + scenario_file::axisElementName(sweep.kind) + ">: ";
    for (const SweepAxis& axis : sweep.axes) {
      if (axis.variable == "terrain.edge" && scenario.step_platforms != StepPlatforms::edge) {
        throw InputError(axis.where, tag + "terrain.edge places a step platform's edge: it needs <terrain "
                                           "step_platforms=\"true\">");
      }
      std::vector<double> values = axis.values;
      if (sweep.kind == SweepSpec::Kind::Random) values = {axis.min, axis.max};
      for (double v : values) {
        if (axis.variable == "platform.trunk_mass_offset" && root && v + p.unreported_trunk_mass <= -root->mass) {
          throw InputError(axis.where, tag + massMessage(v + p.unreported_trunk_mass, p.unreported_trunk_mass != 0));
        }
        if (axis.variable == "platform.unreported_trunk_mass" && root && v + p.trunk_mass_offset <= -root->mass) {
          throw InputError(axis.where, tag + massMessage(v + p.trunk_mass_offset, true));
        }
        if (axis.variable == "contact.mu_static" && v < scenario.sim.contact.mu_dynamic) {
          throw InputError(axis.where, tag + "contact.mu_static values must be >= the contact's mu_dynamic (" +
                                           scenario_file::formatNumber(scenario.sim.contact.mu_dynamic) +
                                           ") (got " + scenario_file::formatNumber(v) + ")");
        }
      }
    }
  }
}

Scenario Loader::load(const std::string& path) {
  files_.push_back(std::make_unique<SourceFile>());
  SourceFile& top = *files_.back();
  const fs::path shown = fs::path(path).lexically_normal();
  checkInputFile(shown.string(), "scenario file", 64ull << 20);  // not found, a pipe, a device, too big
  const XMLElement& root = open(shown, top, SourceLocation{shown.string(), 0});
  include_chain_.push_back(fs::weakly_canonical(shown));
  include_chain_shown_.push_back(top.shown);
  readRoot(root, top, true);

  Scenario scenario;
  scenario.file = fs::absolute(shown).lexically_normal().string();
  scenario.name = scenario_name_;
  scenario.version = kScenarioFormatVersion;
  dispatch(scenario);
  checkAcrossElements(scenario);
  return scenario;
}

}  // namespace

void setParam(std::vector<ParamSetting>& params, const ParamSetting& setting) {
  const auto same =
      std::find_if(params.begin(), params.end(), [&](const ParamSetting& p) { return p.name == setting.name; });
  if (same != params.end()) {
    *same = setting;
  } else {
    params.push_back(setting);
  }
}

Scenario loadScenario(const std::string& path) { return Loader().load(path); }

Scenario loadScenarioPart(const std::string& path) { return Loader(true).load(path); }

bool isScenarioPart(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;  // loadScenario says why (a pipe would block here)
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return false;
  return std::string(doc.RootElement()->Name()) == kPartRoot;
}

}  // namespace pronk
