#include "case_result.h"

#include <cmath>
#include <limits>
#include <string>

#include "pronk/error.h"

namespace pronk {

namespace {

using nlohmann::json;

json number(double v) { return std::isfinite(v) ? json(v) : (std::isnan(v) ? json() : json(v > 0 ? "inf" : "-inf")); }

double numberOf(const json& j) {
  if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    throw Error("case result: not a number: " + s);
  }
  return j.get<double>();
}

json vector(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(number(v[i]));
  return a;
}

json vector(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}

std::vector<double> doubles(const json& a) {
  std::vector<double> v;
  for (const json& x : a) v.push_back(numberOf(x));
  return v;
}

Eigen::VectorXd eigen(const json& a) {
  const std::vector<double> v = doubles(a);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

CaseResult caseResultOf(const EpisodeRecord& record, const CaseDraw* draw,
                        const std::vector<std::string>& penalty_names) {
  CaseResult c;
  c.index = record.index;
  if (!record.setup_error) c.outcome = judgeJump(record);
  c.observation = record.result.observation;
  c.reward = record.result.reward;
  c.action = record.result.action;
  if (draw) c.draw = *draw;
  for (const std::string& name : penalty_names) {
    const double* v = record.result.episode.trace.findMetric(name);
    c.penalties.push_back(v ? *v : std::numeric_limits<double>::quiet_NaN());
  }
  return c;
}

json toJson(const CaseResult& c) {
  json j = {{"index", c.index},
            {"observation", vector(c.observation)},
            {"reward", number(c.reward)},
            {"action", vector(c.action)},
            {"penalties", vector(c.penalties)},
            {"draw",
             {{"ran", c.draw.ran},
              {"residual", vector(c.draw.residual)},
              {"prior", vector(c.draw.prior)},
              {"aim_taken", vector(c.draw.aim_taken)}}}};
  if (c.outcome) {
    const Landing& l = c.outcome->landing;
    j["outcome"] = {{"status", c.outcome->status},
                    {"reason", c.outcome->reason},
                    {"ran", c.outcome->ran},
                    {"landing",
                     {{"displacement", vector(Eigen::VectorXd(l.displacement))},
                      {"yaw", number(l.yaw)},
                      {"error_xy", number(l.error_xy)},
                      {"height", number(l.height)},
                      {"error", number(l.error)},
                      {"error_yaw", number(l.error_yaw)},
                      {"tilt", number(l.tilt)},
                      {"standing", l.standing},
                      {"end_failure", l.end_failure}}}};
  }
  return j;
}

CaseResult caseResultFromJson(const json& j) {
  try {
    CaseResult c;
    c.index = j.at("index").get<size_t>();
    c.observation = doubles(j.at("observation"));
    c.reward = numberOf(j.at("reward"));
    c.action = doubles(j.at("action"));
    c.penalties = doubles(j.at("penalties"));
    const json& d = j.at("draw");
    c.draw.ran = d.at("ran").get<bool>();
    c.draw.residual = eigen(d.at("residual"));
    c.draw.prior = eigen(d.at("prior"));
    c.draw.aim_taken = eigen(d.at("aim_taken"));
    if (j.contains("outcome")) {
      const json& o = j.at("outcome");
      JumpOutcome out;
      out.status = o.at("status").get<std::string>();
      out.reason = o.at("reason").get<std::string>();
      out.ran = o.at("ran").get<bool>();
      const json& l = o.at("landing");
      const Eigen::VectorXd p = eigen(l.at("displacement"));
      if (p.size() != 3) throw Error("case result: a displacement of " + std::to_string(p.size()) + " numbers");
      out.landing.displacement = p;
      out.landing.yaw = numberOf(l.at("yaw"));
      out.landing.error_xy = numberOf(l.at("error_xy"));
      out.landing.height = numberOf(l.at("height"));
      out.landing.error = numberOf(l.at("error"));
      out.landing.error_yaw = numberOf(l.at("error_yaw"));
      out.landing.tilt = numberOf(l.at("tilt"));
      out.landing.standing = l.at("standing").get<bool>();
      out.landing.end_failure = l.at("end_failure").get<std::string>();
      c.outcome = out;
    }
    return c;
  } catch (const json::exception& e) {
    throw Error(std::string("case result: ") + e.what());
  }
}

}  // namespace pronk
