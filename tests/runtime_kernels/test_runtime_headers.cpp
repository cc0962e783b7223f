// Each device header that kernels compiled at run time may include (embedded in the library by
// cmake/embed_headers.cmake) compiles under NVRTC on its own. NVRTC refuses what nvcc accepts in
// these headers, a function without __host__ __device__ or the standard library, and the tests that
// would find out need a GPU; NVRTC itself needs none, so this runs wherever the CUDA toolkit is
// (scripts/build_cuda_check.sh runs it on the CI machine).
#include <nvrtc.h>

#include <cstdio>
#include <string>
#include <vector>

#include "backends/cuda/runtime_kernel_headers.hpp"


namespace {

// The compiler's messages for a program that includes `header` alone, or "" when it compiles.
std::string compile_alone(const std::string& header) {
    using structmd::kRuntimeKernelHeaderCount;
    using structmd::kRuntimeKernelHeaders;
    std::vector<const char*> names, texts;
    for (int h = 0; h < kRuntimeKernelHeaderCount; ++h) {
        names.push_back(kRuntimeKernelHeaders[h].name);
        texts.push_back(kRuntimeKernelHeaders[h].text);
    }
    const std::string source = "#include \"" + header + "\"\n";
    nvrtcProgram program = nullptr;
    if (nvrtcCreateProgram(&program, source.c_str(), "header_check.cu", kRuntimeKernelHeaderCount, texts.data(),
                           names.data()) != NVRTC_SUCCESS)
        return "nvrtcCreateProgram failed";
    // A virtual architecture: no GPU is asked which one it is.
    const char* options[] = {"--std=c++17", "--gpu-architecture=compute_90"};
    const nvrtcResult result = nvrtcCompileProgram(program, 2, options);
    std::string log;
    if (result != NVRTC_SUCCESS) {
        size_t size = 0;
        nvrtcGetProgramLogSize(program, &size);
        log.resize(size);
        nvrtcGetProgramLog(program, log.data());
        log = std::string(nvrtcGetErrorString(result)) + "\n" + log;
    }
    nvrtcDestroyProgram(&program);
    return log;
}

}  // namespace

int main() {
    int failed = 0;
    for (int h = 0; h < structmd::kRuntimeKernelHeaderCount; ++h) {
        const std::string header = structmd::kRuntimeKernelHeaders[h].name;
        const std::string log = compile_alone(header);
        if (log.empty()) continue;
        ++failed;
        std::printf("%s does not compile under NVRTC:\n%s\n", header.c_str(), log.c_str());
    }
    std::printf("%d of %d runtime kernel headers compile under NVRTC\n", structmd::kRuntimeKernelHeaderCount - failed,
                structmd::kRuntimeKernelHeaderCount);
    return failed == 0 ? 0 : 1;
}
