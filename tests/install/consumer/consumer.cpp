// Loads a scenario and a plugin with the installed host libraries, runs a
// short episode with the plugin's controller.
#include <pronk/controller.h>
#include <pronk/episode.h>
#include <pronk/plugin_registry.h>
#include <pronk/scenario.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  try {
    const pronk::Scenario scenario = pronk::loadScenario(argv[1]);
    pronk::PluginRegistry registry;
    registry.load(argv[2]);
    const pronk_factory* factory = registry.find(PRONK_FACTORY_CONTROLLER, "limp");
    if (!factory) return 3;
    pronk::World world(scenario);
    pronk::PluginController controller(*factory, argv[2], pronk::ResolvedParams(), world, nullptr);
    const pronk::EpisodeResult result = pronk::runEpisode(world, controller, {0.05});
    std::printf("consumer: %zu samples, trunk z %.4f m\n", result.trace.samples.size(),
                result.trace.samples.back().base_position.z());
    return result.trace.samples.size() == 51 ? 0 : 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
