// RolloutPool: worker threads, one World each, cases handed out by index and
// records delivered in case order (pronk/rollout.h).
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "pronk/controller.h"
#include "pronk/controller_factory.h"
#include "pronk/rollout.h"
#include "pronk/world.h"

namespace pronk {

struct RolloutPool::Worker {
  std::unique_ptr<World> world;
  // The case assignments the world was built with, but terrain.edge: applyCase
  // changes nothing else of the robot or the simulation, only the terrain and
  // the start pose, which a reused world takes at its restart.
  std::vector<std::pair<std::string, double>> assignments;
};

namespace {

// What a case's world is built from: its assignments but the terrain's.
std::vector<std::pair<std::string, double>> worldAssignments(const EpisodeCase& episode) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& a : episode.assignments) {
    if (a.first != "terrain.edge") out.push_back(a);
  }
  return out;
}

}  // namespace

RolloutPool::RolloutPool(RolloutSetup setup, RolloutOptions options)
    : setup_(std::move(setup)), options_(options) {
  if (!setup_.factory) throw Error("RolloutPool: no environment factory");
  if (!setup_.policy) throw Error("RolloutPool: no policy");
  if (options_.threads < 1) options_.threads = 1;
  if (options_.record_body_poses) options_.record_samples = true;
  UrdfOptions urdf;
  urdf.package_paths = setup_.scenario.platform.package_paths;
  robot_ = std::make_shared<const RobotDescription>(loadUrdf(setup_.scenario.platform.urdf, urdf));
  const Scenario& sc = setup_.scenario;
  footprint_ = World(*robot_, sc.platform, sc.sim, Terrain(sc.ground, sc.ground_height, sc.terrain)).footprint();
  for (int i = 0; i < options_.threads; ++i) workers_.push_back(std::make_unique<Worker>());
}

RolloutPool::~RolloutPool() = default;

EpisodeRecord RolloutPool::runCase(Worker& worker, size_t index, const EpisodeCase& episode) {
  EpisodeRecord record;
  record.index = index;
  record.episode = episode;
  Scenario s;
  try {
    s = applyCase(setup_.scenario, episode, footprint_);
  } catch (const InputError& e) {
    record.setup_error = e.what();
    record.setup_refused = dynamic_cast<const NoRoomForEdge*>(&e) != nullptr;
    record.result.task = {episode.target.x, episode.target.y, episode.target.z,
                          episode.target.yaw, episode.target.roll, episode.target.pitch};
    return record;
  }
  Terrain terrain(s.ground, s.ground_height, s.terrain);
  std::vector<std::pair<std::string, double>> built_from = worldAssignments(episode);
  if (!options_.reuse_worlds || !worker.world || worker.assignments != built_from) {
    worker.world = std::make_unique<World>(*robot_, s.platform, s.sim, terrain);
    worker.assignments = std::move(built_from);
    ++worlds_built_;
  } else {
    worker.world->restart(s.platform.base_position, s.platform.base_yaw, std::move(terrain));
  }
  EpisodeOptions options;
  options.duration = options_.max_episode_s;
  options.record_samples = options_.record_samples;
  options.record_body_poses = options_.record_body_poses;
  options.end_at_rest = options_.end_at_rest;
  options.apex_platform = s.apex_platform;
  const TargetSpec& t = episode.target;
  try {
    record.result = runEnvironmentEpisode(*worker.world, *setup_.factory, setup_.origin, setup_.params,
                                          {t.x, t.y, t.z, t.yaw, t.roll, t.pitch}, index, setup_.policy, options);
  } catch (const Error& e) {
    // The environment or the policy failed on this case (a plugin error, an
    // action it refuses to take as an error): the case fails alone, with the
    // reason; its World is not reused.
    worker.world.reset();
    record.result = EnvironmentEpisodeResult{};
    record.result.task = {t.x, t.y, t.z, t.yaw, t.roll, t.pitch};
    record.result.episode.failure = Failure{0.0, "error", e.what()};
  }
  return record;
}

size_t RolloutPool::run(const std::vector<EpisodeCase>& cases, const EpisodeSink& sink) {
  std::vector<size_t> all(cases.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  return run(cases, all, sink);
}

size_t RolloutPool::run(const std::vector<EpisodeCase>& cases, const std::vector<size_t>& which,
                        const EpisodeSink& sink) {
  for (size_t i : which)
    if (i >= cases.size()) throw Error("RolloutPool::run: case index " + std::to_string(i) + " out of range");
  stop_ = false;
  std::mutex mutex;
  std::condition_variable ready;
  std::map<size_t, EpisodeRecord> finished;   // out of order, until their turn
  std::map<size_t, std::exception_ptr> errors;
  size_t next_case = 0;
  const size_t threads = std::min(workers_.size(), std::max<size_t>(which.size(), 1));

  auto work = [&](Worker& worker) {
    for (;;) {
      size_t position;  // in `which`
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (stop_ || (options_.stop && *options_.stop) || next_case >= which.size()) {
          if (next_case < which.size()) stop_ = true;
          ready.notify_all();  // the delivering thread may be waiting for a case nobody will run
          return;
        }
        position = next_case++;
      }
      try {
        EpisodeRecord record = runCase(worker, which[position], cases[which[position]]);
        std::lock_guard<std::mutex> lock(mutex);
        finished.emplace(position, std::move(record));
      } catch (...) {
        // A broken world (an exception out of the simulation itself) is not
        // reused; the error reaches the caller in case order.
        worker.world.reset();
        std::lock_guard<std::mutex> lock(mutex);
        errors.emplace(position, std::current_exception());
      }
      ready.notify_all();
    }
  };

  // The workers simulate; the calling thread only delivers, so that a slow sink
  // (a video encoder) overlaps the simulation.
  std::vector<std::thread> pool;
  for (size_t w = 0; w < threads; ++w) pool.emplace_back(work, std::ref(*workers_[w]));
  std::exception_ptr failure;
  size_t delivered = 0;
  for (; delivered < which.size(); ++delivered) {
    EpisodeRecord record;
    {
      std::unique_lock<std::mutex> lock(mutex);
      ready.wait(lock, [&] {
        return finished.count(delivered) || errors.count(delivered) || (stop_ && delivered >= next_case);
      });
      if (auto e = errors.find(delivered); e != errors.end()) {
        failure = e->second;
        stop_ = true;
        break;
      }
      auto it = finished.find(delivered);
      if (it == finished.end()) break;  // stopped before this case was handed out
      record = std::move(it->second);
      finished.erase(it);
    }
    try {
      sink(record);
    } catch (...) {
      failure = std::current_exception();
      stop_ = true;
      ++delivered;
      break;
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    stop_ = stop_ || delivered < which.size();
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return delivered;
}

std::vector<std::optional<std::vector<double>>> RolloutPool::priorActions(
    const std::vector<std::vector<double>>& tasks) {
  const Scenario& s = setup_.scenario;
  if (!planning_world_) {
    planning_world_ = std::make_unique<World>(*robot_, s.platform, s.sim, Terrain(s.ground, s.ground_height, s.terrain));
  }
  checkFactoryFitsWorld(*setup_.factory, PRONK_FACTORY_ENVIRONMENT, setup_.origin, *planning_world_);
  Trace reported;  // the environment's log lines and metrics, unused
  const HostApi host(*planning_world_, &reported);
  EnvironmentInstance env(*setup_.factory, setup_.origin, *host.api(), setup_.params);
  const AbiStateView view(planning_world_->state());
  std::vector<std::optional<std::vector<double>>> out;
  out.reserve(tasks.size());
  for (size_t i = 0; i < tasks.size(); ++i) {
    try {
      const std::vector<double> observation = env.reset(tasks[i], i, *view.get());
      out.push_back(env.priorAction(observation));
    } catch (const Error&) {
      out.push_back(std::nullopt);
    }
  }
  return out;
}

RolloutSetup environmentSetup(const Scenario& scenario, const PluginRegistry& registry,
                              const std::vector<ParamSetting>& overrides, const std::string& policy_name) {
  if (!scenario.environment) throw InputError({scenario.file, 0}, "the scenario has no <environment>");
  const EnvironmentSpec& spec = *scenario.environment;
  RolloutSetup setup;
  setup.scenario = scenario;
  setup.factory = &findEnvironment(spec, registry);
  setup.origin = registry.libraryOf(setup.factory)->path();
  setup.schema = environmentSchema(*setup.factory);
  std::vector<ParamSetting> params = spec.params;
  for (const ParamSetting& p : overrides) setParam(params, p);
  setup.params = resolveParams(*setup.factory, params, spec.where, &scenario.platform);
  if (!policy_name.empty()) {
    setup.policy = makePolicy(policy_name, *setup.factory, scenario.platform.name, &setup.warnings);
  }
  return setup;
}

}  // namespace pronk
