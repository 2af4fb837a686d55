// An environment factory's episode on a World: the host side of the ABI's
// reset / act / step / finish cycle.
#include <algorithm>

#include "pronk/controller.h"
#include "pronk/episode.h"

namespace pronk {
namespace {

// The environment's step() behind the Controller interface, so that the episode
// loop (sampling, contact events, failures) is the one every controller uses.
class EnvironmentTicks : public Controller {
 public:
  EnvironmentTicks(EnvironmentInstance& env, int joints) : env_(env), joints_(joints) {}
  Eigen::VectorXd compute(const RobotState& state) override {
    const AbiStateView view(state);
    Eigen::VectorXd tau = Eigen::VectorXd::Zero(joints_);
    done_ = env_.step(*view.get(), tau.data());
    return tau;
  }
  bool finished() const override { return done_; }

 private:
  EnvironmentInstance& env_;
  int joints_;
  bool done_ = false;
};

}  // namespace

EnvironmentEpisodeResult runEnvironmentEpisode(World& world, const pronk_factory& factory, const std::string& origin,
                                               const ResolvedParams& params, const std::vector<double>& task,
                                               uint64_t seed, const Policy& policy, const EpisodeOptions& options) {
  checkFactoryFitsWorld(factory, PRONK_FACTORY_ENVIRONMENT, origin, world);
  EnvironmentEpisodeResult out;
  out.task = task;
  Trace plugin;  // what the environment reports: events and metrics
  const HostApi host(world, &plugin);
  EnvironmentInstance env(factory, origin, *host.api(), params);
  {
    // Alive until act(): the policy may retask() the environment (an aim correction).
    const AbiStateView view(world.state());
    out.observation = env.reset(task, seed, *view.get());
    out.action = policy(out.observation, env, seed);
    out.rejected = env.act(out.action);
  }
  if (out.rejected) {
    out.episode.trace.joint_names = world.jointNames();
    out.episode.trace.foot_links = world.footLinks();
    out.episode.trace.events = plugin.events;  // what the environment said before it refused
    out.episode.trace.addEvent(world.time(), "rejected", *out.rejected);
    out.episode.trace.metrics = plugin.metrics;
    return out;
  }
  EnvironmentTicks ticks(env, world.jointCount());
  out.episode = runEpisode(world, ticks, options);
  {
    const AbiStateView view(world.state());
    try {
      out.environment_reward = env.finish(*view.get());
    } catch (const Error& e) {
      if (!out.episode.failure) out.episode.failure = Failure{world.time(), "environment", e.what()};
    }
  }
  out.reward = out.episode.failure ? 0.0 : out.environment_reward;
  Trace& trace = out.episode.trace;
  trace.events.insert(trace.events.end(), plugin.events.begin(), plugin.events.end());
  std::stable_sort(trace.events.begin(), trace.events.end(),
                   [](const TraceEvent& a, const TraceEvent& b) { return a.time < b.time; });
  trace.metrics = plugin.metrics;
  return out;
}

}  // namespace pronk
