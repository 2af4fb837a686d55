// <sim>: control rate, integrator, step, duration, gravity, and the foot
// <contact> law.
#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

ContactSpec readContact(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  ContactSpec c;
  c.where = r.where();
  c.model = r.choice("model", c.model, kContactModels);
  c.stiffness = r.number("stiffness", c.stiffness, Range::positive());
  c.dissipation = r.number("dissipation", c.dissipation, Range::nonNegative());
  c.mu_static = r.number("mu_static", c.mu_static, Range::nonNegative());
  c.mu_dynamic = r.number("mu_dynamic", c.mu_dynamic, Range::nonNegative());
  c.tangential_stiffness = r.number("tangential_stiffness", c.tangential_stiffness, Range::positive());
  c.tangential_damping = r.number("tangential_damping", c.tangential_damping, Range::nonNegative());
  c.implicit = r.boolean("implicit", c.implicit);
  r.rejectUnknownAttributes();
  r.children({});
  if (c.mu_dynamic > c.mu_static) {
    r.fail("mu_dynamic (" + formatNumber(c.mu_dynamic) + ") must be <= mu_static (" + formatNumber(c.mu_static) +
           "): sliding friction cannot exceed sticking friction");
  }
  return c;
}

}  // namespace

SimSpec readSim(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  SimSpec s;
  s.where = r.where();
  s.control_rate = r.number("control_rate", s.control_rate, Range::positive());
  s.integrator = r.choice("integrator", s.integrator, kIntegrators);
  s.step = r.number("step", s.step, Range::positive());
  s.accuracy = r.number("accuracy", s.accuracy, Range::open(0, 1));
  s.flight_max_step = r.number("flight_max_step", s.flight_max_step, Range::positive());
  s.duration = r.number("duration", s.duration, Range{0, kMaxEpisodeSeconds, true, false});
  s.max_steps_per_second = r.number("max_steps_per_second", s.max_steps_per_second, Range::atLeast(1e3));
  s.gravity = r.vec3("gravity", s.gravity);
  r.rejectUnknownAttributes();
  const double period = 1 / s.control_rate;
  if (s.step > period * (1 + 1e-9)) {
    r.fail("step (" + formatNumber(s.step) + " s) must be <= the control period 1/control_rate (" +
           formatNumber(period) + " s)");
  }
  const auto kids = r.children({"contact"});
  r.rejectRepeated(kids, "contact");
  s.contact.where = s.where;
  for (const XMLElement* k : kids) s.contact = readContact(*k, file);
  return s;
}

}  // namespace pronk::scenario_file
