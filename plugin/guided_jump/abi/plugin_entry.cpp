// The plugin's one exported symbol: the ABI handshake and the manifest.
#include <atomic>
#include <cstddef>

#include "abi/abi_boundary.h"
#include "abi/factories.h"

#ifndef PRONK_VERSION
#error "PRONK_VERSION must be defined by the build"
#endif

namespace pronk::guided_jump {
namespace {
std::atomic<uint32_t> g_negotiated_minor{0};
}  // namespace
void setNegotiatedAbiMinor(uint32_t minor) { g_negotiated_minor = minor; }
uint32_t negotiatedAbiMinor() { return g_negotiated_minor; }
}  // namespace pronk::guided_jump

extern "C" PRONK_PLUGIN_EXPORT pronk_status pronk_plugin_query(uint32_t host_abi_version, pronk_plugin_manifest* manifest,
                                                               char* error, size_t error_size) {
  using namespace pronk::guided_jump;
  if (PRONK_ABI_VERSION_MAJOR(host_abi_version) != PRONK_ABI_MAJOR) {
    char message[160];
    std::snprintf(message, sizeof message, "pronk_guided_jump speaks plugin ABI %u.%u; the host offers %u.%u",
                  PRONK_ABI_MAJOR, PRONK_ABI_MINOR, PRONK_ABI_VERSION_MAJOR(host_abi_version),
                  PRONK_ABI_VERSION_MINOR(host_abi_version));
    writeError(error, error_size, message);
    return PRONK_ERROR_VERSION;
  }
  constexpr size_t kManifestSize_1_0 = offsetof(pronk_plugin_manifest, factories) + sizeof(pronk_plugin_manifest::factories);
  if (!manifest || manifest->struct_size < kManifestSize_1_0) {
    writeError(error, error_size, "the manifest is missing or smaller than ABI 1.0's");
    return PRONK_ERROR_INVALID_ARGUMENT;
  }
  return guarded(error, error_size, [&] {
    static const pronk_factory* const factories[] = {guidedJumpControllerFactory(), jumpEnvironmentFactory()};
    const uint32_t host_minor = PRONK_ABI_VERSION_MINOR(host_abi_version);
    manifest->abi_version = PRONK_ABI_VERSION(PRONK_ABI_MAJOR, host_minor > PRONK_ABI_MINOR ? PRONK_ABI_MINOR : host_minor);
    setNegotiatedAbiMinor(PRONK_ABI_VERSION_MINOR(manifest->abi_version));
    manifest->plugin_name = "pronk_guided_jump";
    manifest->plugin_version = PRONK_VERSION;
    manifest->factory_count = sizeof(factories) / sizeof(factories[0]);
    manifest->factories = factories;
  });
}
