// The CUDA side of devices.hpp and engine_instances.hpp where the CUDA backend is the module
// libstructmd_cuda.so (engines/cuda_module.hpp): the module is looked for beside this library and
// loaded on first use; where it or a CUDA library it needs cannot be loaded, no GPU is usable, the
// CPU backend works as ever, and asking for the CUDA backend says what is missing.
#include <dlfcn.h>

#include <string>

#include "core/error.hpp"
#include "engines/cuda_module.hpp"
#include "engines/devices.hpp"
#include "engines/plugin_abi.hpp"

namespace structmd {

namespace {

struct LoadedCudaModule {
    const CudaModuleEntries* entries = nullptr;
    std::string failure;  // why entries is null
};

std::string dl_error() {
    const char* text = dlerror();
    return text ? text : "unknown reason";
}

// The folder of the library this code is linked into: the module lies beside it.
std::string own_folder() {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<const void*>(&own_folder), &info) || !info.dli_fname) return {};
    const std::string path = info.dli_fname;
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

LoadedCudaModule load_cuda_module() {
    const std::string path = own_folder() + kCudaModuleFile;
    const std::string needs = "; the CUDA backend needs the CUDA " STRUCTMD_CUDA_MAJOR_STRING
                              " libraries: pip install structmd-engine[cuda], or a CUDA toolkit on the library search path";
    dlerror();
    // RTLD_NODELETE: engines made by the module live as long as their handles; it stays loaded.
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!module) return {nullptr, "the CUDA backend cannot be loaded: " + dl_error() + needs};
    const auto entries_of = reinterpret_cast<CudaModuleEntriesFn>(dlsym(module, kCudaModuleEntriesSymbol));
    if (!entries_of) return {nullptr, path + " is not structmd's CUDA module: " + dl_error()};
    const CudaModuleEntries* entries = entries_of();
    const std::string build = entries && entries->build ? entries->build : "";
    if (build != STRUCTMD_PLUGIN_BUILD)
        return {nullptr, path + " was built as \"" + build + "\", but this library is \"" + STRUCTMD_PLUGIN_BUILD +
                             "\"; reinstall structmd"};
    return {entries, {}};
}

// Loaded once per process, on first use, and never changed after: the process's libraries, not
// state of a handle.
const LoadedCudaModule& cuda_module() {
    static const LoadedCudaModule loaded = load_cuda_module();
    return loaded;
}

const CudaModuleEntries& entries() {
    const LoadedCudaModule& loaded = cuda_module();
    if (!loaded.entries) throw Error(STRUCTMD_ERR_UNSUPPORTED, loaded.failure);
    return *loaded.entries;
}

std::unique_ptr<LocalEngine> make_engine(MakeCudaEngineFn make, int device, SimulationSpec spec,
                                         const ForceFieldComponents& components, const Logger& log) {
    if (!make) throw Error(STRUCTMD_ERR_INTERNAL, "the CUDA module lacks a precision that this library has");
    return make(device, std::move(spec), components, log);
}

}  // namespace

std::string cuda_backend_unavailable() { return cuda_module().failure; }

int usable_gpu_count() {
    const LoadedCudaModule& loaded = cuda_module();
    return loaded.entries ? loaded.entries->usable_gpu_count() : 0;
}

std::string gpu_name(int device) { return entries().gpu_name(device); }

std::unique_ptr<LocalEngine> make_cuda_engine_single(int device, SimulationSpec spec,
                                                    const ForceFieldComponents& components, const Logger& log) {
    return make_engine(entries().make_engine_single, device, std::move(spec), components, log);
}
std::unique_ptr<LocalEngine> make_cuda_engine_mixed(int device, SimulationSpec spec,
                                                   const ForceFieldComponents& components, const Logger& log) {
    return make_engine(entries().make_engine_mixed, device, std::move(spec), components, log);
}
std::unique_ptr<LocalEngine> make_cuda_engine_double(int device, SimulationSpec spec,
                                                    const ForceFieldComponents& components, const Logger& log) {
    return make_engine(entries().make_engine_double, device, std::move(spec), components, log);
}

}  // namespace structmd
