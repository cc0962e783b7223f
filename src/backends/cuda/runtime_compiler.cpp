#include "backends/cuda/runtime_compiler.hpp"

#include <cuda_runtime.h>
#include <nvrtc.h>

#include <chrono>
#include <memory>

#include "backends/cuda/cuda_check.hpp"
#include "backends/cuda/runtime_kernel_headers.hpp"
#include "core/error.hpp"

namespace structmd {

namespace {

void nvrtc_check(nvrtcResult status, const char* what) {
    if (status != NVRTC_SUCCESS)
        throw Error(STRUCTMD_ERR_DEVICE, std::string(what) + ": " + nvrtcGetErrorString(status));
}

struct Program {
    nvrtcProgram handle = nullptr;
    ~Program() { nvrtcDestroyProgram(&handle); }

    std::string log() const {
        size_t size = 0;
        nvrtcGetProgramLogSize(handle, &size);
        std::string text(size, '\0');
        nvrtcGetProgramLog(handle, text.data());
        return text;
    }
};

}  // namespace

RuntimeKernels::RuntimeKernels(int device, const std::string& source, const std::vector<std::string>& kernels) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<const char*> headerTexts, headerNames;
    for (int h = 0; h < kRuntimeKernelHeaderCount; ++h) {
        headerNames.push_back(kRuntimeKernelHeaders[h].name);
        headerTexts.push_back(kRuntimeKernelHeaders[h].text);
    }
    Program program;
    nvrtc_check(nvrtcCreateProgram(&program.handle, source.c_str(), "runtime_kernel.cu", kRuntimeKernelHeaderCount,
                                   headerTexts.data(), headerNames.data()),
                "creating a runtime kernel");
    for (const std::string& kernel : kernels)
        nvrtc_check(nvrtcAddNameExpression(program.handle, kernel.c_str()), "naming a runtime kernel");

    int major = 0, minor = 0;
    cuda_check(cudaDeviceGetAttribute(&major, cudaDevAttrComputeCapabilityMajor, device), "reading the GPU's version");
    cuda_check(cudaDeviceGetAttribute(&minor, cudaDevAttrComputeCapabilityMinor, device), "reading the GPU's version");
    const std::string arch = "--gpu-architecture=sm_" + std::to_string(10 * major + minor);
    const char* options[] = {"--std=c++17", arch.c_str()};
    const nvrtcResult compiled = nvrtcCompileProgram(program.handle, 2, options);
    if (compiled != NVRTC_SUCCESS)
        throw Error(STRUCTMD_ERR_INTERNAL, "a runtime kernel did not compile (" +
                                               std::string(nvrtcGetErrorString(compiled)) + "):\n" + program.log() +
                                               "\nsource:\n" + source);
    size_t size = 0;
    nvrtc_check(nvrtcGetCUBINSize(program.handle, &size), "reading a runtime kernel");
    std::string cubin(size, '\0');
    nvrtc_check(nvrtcGetCUBIN(program.handle, cubin.data()), "reading a runtime kernel");

    cudaLibrary_t library = nullptr;
    cuda_check(cudaLibraryLoadData(&library, cubin.data(), nullptr, nullptr, 0, nullptr, nullptr, 0),
               "loading a runtime kernel");
    library_ = library;
    try {
        for (const std::string& kernel : kernels) {
            const char* lowered = nullptr;
            nvrtc_check(nvrtcGetLoweredName(program.handle, kernel.c_str(), &lowered), "naming a runtime kernel");
            cudaKernel_t handle = nullptr;
            cuda_check(cudaLibraryGetKernel(&handle, library, lowered), "finding a runtime kernel");
            kernels_.push_back(reinterpret_cast<const void*>(handle));
        }
    } catch (...) {
        cudaLibraryUnload(library);
        throw;
    }
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RuntimeKernels::~RuntimeKernels() {
    if (library_) cudaLibraryUnload(static_cast<cudaLibrary_t>(library_));
}

}  // namespace structmd
