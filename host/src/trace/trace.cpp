#include "pronk/trace.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <iomanip>

#include "pronk/error.h"
#include "pronk/file_io.h"

namespace pronk {

void writeTraceCsv(const Trace& trace, const std::string& path) {
  // Composed whole, then written beside and renamed: a failed write leaves no
  // trace cut mid-number.
  std::ostringstream out;
  out << std::setprecision(9);
  out << "time,base_x,base_y,base_z,base_qw,base_qx,base_qy,base_qz,com_x,com_y,com_z,com_vx,com_vy,com_vz";
  for (const std::string& j : trace.joint_names) out << ",q_" << j;
  for (const std::string& j : trace.joint_names) out << ",qd_" << j;
  for (const std::string& j : trace.joint_names) out << ",tau_" << j;
  for (const std::string& f : trace.foot_links) {
    out << ',' << f << "_contact," << f << "_x," << f << "_y," << f << "_z," << f << "_fx," << f << "_fy," << f << "_fz";
  }
  out << '\n';
  for (const TraceSample& s : trace.samples) {
    out << s.time;
    for (int i = 0; i < 3; ++i) out << ',' << s.base_position(i);
    for (int i = 0; i < 4; ++i) out << ',' << s.base_quaternion(i);
    for (int i = 0; i < 3; ++i) out << ',' << s.com_position(i);
    for (int i = 0; i < 3; ++i) out << ',' << s.com_velocity(i);
    for (const Eigen::VectorXd* v : {&s.q, &s.qd, &s.torque})
      for (Eigen::Index i = 0; i < v->size(); ++i) out << ',' << (*v)(i);
    for (size_t f = 0; f < s.foot_position.size(); ++f) {
      out << ',' << int(s.foot_in_contact[f]);
      for (int i = 0; i < 3; ++i) out << ',' << s.foot_position[f](i);
      for (int i = 0; i < 3; ++i) out << ',' << s.foot_force[f](i);
    }
    out << '\n';
  }
  replaceFileAtomically(path, out.str(), "trace file");
}

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

}  // namespace

Trace readTraceCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0}, "cannot open the trace file");
  std::string line;
  if (!std::getline(in, line)) throw InputError({path, 1}, "empty trace file");
  const std::vector<std::string> header = splitCsv(line);
  Trace trace;
  for (const std::string& h : header) {
    if (h.rfind("q_", 0) == 0) trace.joint_names.push_back(h.substr(2));
    const std::string suffix = "_contact";
    if (h.size() > suffix.size() && h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0) {
      trace.foot_links.push_back(h.substr(0, h.size() - suffix.size()));
    }
  }
  const size_t nj = trace.joint_names.size(), nf = trace.foot_links.size();
  const size_t expected = 14 + 3 * nj + 7 * nf;
  if (header.size() != expected || header[0] != "time") {
    throw InputError({path, 1}, "not a pronk trace header (" + std::to_string(header.size()) + " columns, expected " +
                                    std::to_string(expected) + ")");
  }
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsv(line);
    if (f.size() != expected) {
      throw InputError({path, number}, std::to_string(f.size()) + " columns, expected " + std::to_string(expected));
    }
    std::vector<double> v(f.size());
    for (size_t i = 0; i < f.size(); ++i) {
      size_t used = 0;
      try {
        v[i] = std::stod(f[i], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != f[i].size() || f[i].empty()) {
        throw InputError({path, number}, "column '" + header[i] + "': '" + f[i] + "' is not a number");
      }
      // A recorded state is finite: nan or inf would reach the kinematics as a pose.
      if (!std::isfinite(v[i])) {
        throw InputError({path, number}, "column '" + header[i] + "': '" + f[i] + "' is not a finite number");
      }
    }
    TraceSample s;
    size_t k = 0;
    s.time = v[k++];
    for (int i = 0; i < 3; ++i) s.base_position(i) = v[k++];
    for (int i = 0; i < 4; ++i) s.base_quaternion(i) = v[k++];
    for (int i = 0; i < 3; ++i) s.com_position(i) = v[k++];
    for (int i = 0; i < 3; ++i) s.com_velocity(i) = v[k++];
    s.q.resize(Eigen::Index(nj));
    s.qd.resize(Eigen::Index(nj));
    s.torque.resize(Eigen::Index(nj));
    for (Eigen::VectorXd* vec : {&s.q, &s.qd, &s.torque})
      for (size_t i = 0; i < nj; ++i) (*vec)(Eigen::Index(i)) = v[k++];
    for (size_t ft = 0; ft < nf; ++ft) {
      s.foot_in_contact.push_back(v[k++] != 0 ? 1 : 0);
      s.foot_position.emplace_back(v[k], v[k + 1], v[k + 2]);
      s.foot_force.emplace_back(v[k + 3], v[k + 4], v[k + 5]);
      k += 6;
    }
    trace.samples.push_back(std::move(s));
  }
  if (trace.samples.empty()) throw InputError({path, number}, "the trace has no samples");
  return trace;
}

void addContactEvents(Trace& trace) {
  bool airborne = false;
  for (size_t i = 1; i < trace.samples.size(); ++i) {
    bool any = false;
    for (uint8_t c : trace.samples[i].foot_in_contact) any = any || c;
    if (!any && !airborne) trace.addEvent(trace.samples[i].time, "lift_off");
    if (any && airborne) trace.addEvent(trace.samples[i].time, "touchdown");
    airborne = !any;
  }
}

}  // namespace pronk
