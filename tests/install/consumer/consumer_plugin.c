/* The smallest plugin: one controller that commands zero torque. */
#include <pronk/plugin_abi.h>
#include <string.h>

static pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t count,
                           void** instance, char* error, size_t error_size) {
  (void)params; (void)count; (void)error; (void)error_size;
  *instance = (void*)host;
  return PRONK_OK;
}
static pronk_status compute(void* instance, const pronk_robot_state* state, double* torque, char* error,
                            size_t error_size) {
  (void)instance; (void)error; (void)error_size;
  memset(torque, 0, sizeof(double) * (size_t)state->joint_count);
  return PRONK_OK;
}
static void destroy(void* instance) { (void)instance; }

static const pronk_controller_ops ops = {sizeof(pronk_controller_ops), NULL, compute, destroy};
static const pronk_factory limp = {sizeof(pronk_factory), PRONK_FACTORY_CONTROLLER, "limp", "zero torque",
                                   0, NULL, 0, 0, 0, 0.0, create, &ops, NULL};
static const pronk_factory* const factories[] = {&limp};

pronk_status pronk_plugin_query(uint32_t host_version, pronk_plugin_manifest* manifest, char* error,
                                size_t error_size) {
  if (PRONK_ABI_VERSION_MAJOR(host_version) != PRONK_ABI_MAJOR) {
    if (error_size) { strncpy(error, "ABI major mismatch", error_size - 1); error[error_size - 1] = 0; }
    return PRONK_ERROR_VERSION;
  }
  manifest->abi_version = PRONK_ABI_VERSION(PRONK_ABI_MAJOR, 0);
  manifest->plugin_name = "consumer";
  manifest->plugin_version = "1";
  manifest->factory_count = 1;
  manifest->factories = factories;
  return PRONK_OK;
}
