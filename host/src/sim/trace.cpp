#include "pronk/trace.h"

#include <fstream>
#include <iomanip>

#include "pronk/error.h"

namespace pronk {

void writeTraceCsv(const Trace& trace, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write the trace file");
  out << std::setprecision(9);
  out << "time,base_x,base_y,base_z,base_qw,base_qx,base_qy,base_qz,com_x,com_y,com_z,com_vx,com_vy,com_vz";
  for (const std::string& j : trace.joint_names) out << ",q_" << j;
  for (const std::string& j : trace.joint_names) out << ",qd_" << j;
  for (const std::string& j : trace.joint_names) out << ",tau_" << j;
  for (const std::string& f : trace.foot_links) out << ',' << f << "_contact," << f << "_fx," << f << "_fy," << f << "_fz";
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
      for (int i = 0; i < 3; ++i) out << ',' << s.foot_force[f](i);
    }
    out << '\n';
  }
  if (!out) throw Error(path + ": writing the trace failed");
}

}  // namespace pronk
