// Loading plugin libraries (dlopen), the search path, and lookup of factories by
// kind and name.
#include "pronk/plugin_registry.h"

#include "plugin_call.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <filesystem>
#include <set>
#include <system_error>

namespace pronk {

namespace fs = std::filesystem;

namespace {

std::string dlerrorText() {
  const char* e = dlerror();
  return e ? e : "no error text from dlerror()";
}

// The path that identifies a file: canonical when it exists, else absolute.
std::string identityOf(const fs::path& absolute) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(absolute, ec);
  return ec ? absolute.string() : canonical.string();
}

bool hasSoSuffix(const fs::path& p) {
  const std::string name = p.filename().string();
  return name.size() > 3 && name.compare(name.size() - 3, 3, ".so") == 0;
}

}  // namespace

std::string factoryKindName(uint32_t kind) {
  switch (kind) {
    case PRONK_FACTORY_CONTROLLER:
      return "controller";
    case PRONK_FACTORY_ENVIRONMENT:
      return "environment";
    default:
      return "kind " + std::to_string(kind);
  }
}

PluginRegistry::PluginRegistry() = default;

PluginRegistry::~PluginRegistry() {
  // Unload in reverse load order.
  while (!libraries_.empty()) libraries_.pop_back();
}

const PluginLibrary& PluginRegistry::load(const std::string& file) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(fs::path(file), ec).lexically_normal();
  const std::string path = ec ? file : absolute.string();
  const std::string identity = identityOf(path);
  for (const auto& lib : libraries_) {
    if (lib->identity_ == identity) return *lib;
  }

  dlerror();  // clear any earlier error
  // An absolute path, so that dlopen never searches the library path for a bare name.
  void* handle = nullptr;
  {
    const PluginCallScope call(path.c_str(), nullptr, "static constructors (dlopen)");
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  }
  if (!handle) throw Error("cannot load plugin '" + file + "': " + dlerrorText());
  for (const auto& lib : libraries_) {
    if (lib->handle_ == handle) {  // the same file under another name (a link)
      dlclose(handle);
      return *lib;
    }
  }

  dlerror();
  void* entry = dlsym(handle, PRONK_PLUGIN_ENTRY_NAME);
  if (!entry) {
    const std::string why = dlerrorText();
    dlclose(handle);
    throw Error("plugin '" + path + "' does not export the entry point " PRONK_PLUGIN_ENTRY_NAME ": " + why);
  }
  std::unique_ptr<PluginLibrary> library;
  try {
    library = handshake(path, reinterpret_cast<pronk_plugin_query_fn>(entry));
  } catch (...) {
    dlclose(handle);
    throw;
  }
  library->handle_ = handle;  // from here on the library's destructor closes it
  library->identity_ = identity;
  return add(std::move(library));
}

const PluginLibrary& PluginRegistry::loadBuiltin(const std::string& origin, pronk_plugin_query_fn query) {
  const std::string path = "builtin:" + origin;
  for (const auto& lib : libraries_) {
    if (lib->identity_ == path) return *lib;
  }
  if (!query) throw Error("plugin '" + path + "': no entry point given");
  std::unique_ptr<PluginLibrary> library = handshake(path, query);
  library->identity_ = path;
  return add(std::move(library));
}

const PluginLibrary& PluginRegistry::add(std::unique_ptr<PluginLibrary> library) {
  for (const pronk_factory* f : library->factories()) {
    if (const pronk_factory* existing = find(static_cast<pronk_factory_kind>(f->kind), f->name)) {
      throw Error("plugin '" + library->path() + "': " + factoryKindName(f->kind) + " '" + f->name +
                  "' is already registered by plugin '" + libraryOf(existing)->path() + "'");
    }
  }
  libraries_.push_back(std::move(library));
  return *libraries_.back();
}

void PluginRegistry::loadSearchPath(const std::vector<std::string>& entries) {
  std::set<std::string> loaded_names;  // file names already loaded from an earlier entry
  auto loadFile = [&](const fs::path& file, bool found_in_directory) {
    const std::string name = file.filename().string();
    if (loaded_names.count(name)) return;  // shadowed by an earlier entry
    loaded_names.insert(name);
    if (!found_in_directory) {
      load(file.string());
      return;
    }
    // A broken library found in a directory stops only what needs it.
    try {
      load(file.string());
    } catch (const Error& e) {
      skipped_.push_back({file.string(), e.what()});
    }
  };
  for (const std::string& entry : entries) {
    if (entry.empty()) continue;
    std::error_code ec;
    const fs::file_status st = fs::status(entry, ec);
    if (ec || !fs::exists(st)) throw Error("plugin path entry '" + entry + "' does not exist");
    if (!fs::is_directory(st)) {
      loadFile(entry, false);
      continue;
    }
    std::vector<fs::path> files;
    for (fs::directory_iterator it(entry, ec), end; !ec && it != end; it.increment(ec)) {
      std::error_code file_ec;
      if (hasSoSuffix(it->path()) && it->is_regular_file(file_ec)) files.push_back(it->path());  // follows links
    }
    if (ec) throw Error("cannot read plugin directory '" + entry + "': " + ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) loadFile(file, true);
  }
}

std::string PluginRegistry::skippedNote() const {
  std::string note;
  for (const Skipped& s : skipped_) note += (note.empty() ? "; not loaded: " : ", ") + s.path + " (" + s.reason + ")";
  return note;
}

std::vector<std::string> PluginRegistry::defaultDirectories() {
  std::vector<std::string> out;
  auto addUnique = [&](const fs::path& dir) {
    const std::string id = identityOf(dir.lexically_normal());
    if (std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
  };
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) addUnique(exe.parent_path() / ".." / PRONK_PLUGIN_RELATIVE_DIR);
  addUnique(fs::path(PRONK_PLUGIN_INSTALL_DIR));
  return out;
}

std::vector<std::string> PluginRegistry::searchPath(const std::vector<std::string>& explicit_entries) {
  std::vector<std::string> out(explicit_entries.begin(), explicit_entries.end());
  if (const char* env = std::getenv("PRONK_PLUGIN_PATH")) {
    const std::string value = env;
    size_t start = 0;
    while (start <= value.size()) {
      const size_t colon = std::min(value.find(':', start), value.size());
      if (colon > start) out.push_back(value.substr(start, colon - start));
      start = colon + 1;
    }
  }
  for (const std::string& dir : defaultDirectories()) {
    std::error_code ec;
    if (fs::is_directory(dir, ec)) out.push_back(dir);
  }
  return out;
}

const pronk_factory* PluginRegistry::find(pronk_factory_kind kind, const std::string& name) const {
  for (const auto& lib : libraries_) {
    for (const pronk_factory* f : lib->factories()) {
      if (f->kind == static_cast<uint32_t>(kind) && name == f->name) return f;
    }
  }
  return nullptr;
}

const PluginLibrary* PluginRegistry::libraryOf(const pronk_factory* factory) const {
  for (const auto& lib : libraries_) {
    for (const pronk_factory* f : lib->factories()) {
      if (f == factory) return lib.get();
    }
  }
  return nullptr;
}

std::vector<const PluginLibrary*> PluginRegistry::libraries() const {
  std::vector<const PluginLibrary*> out;
  for (const auto& lib : libraries_) out.push_back(lib.get());
  return out;
}

}  // namespace pronk
