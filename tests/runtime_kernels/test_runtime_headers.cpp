// Each device header that kernels compiled at run time may include (embedded in the library by
// cmake/embed_headers.cmake) compiles under NVRTC on its own. NVRTC refuses what nvcc accepts in
// these headers, a function without __host__ __device__ or the standard library, and the tests that
// would find out need a GPU; NVRTC itself needs none, so this runs wherever the CUDA toolkit is
// (scripts/build_cuda_check.sh runs it on the CI machine). The expression transverser's kernels, as the
// engine writes them (simulation/expression_transverser.hpp), are instantiated too: a template body
// (the lanes' combine, the traversals) is checked only where it is instantiated.
#include <nvrtc.h>

#include <cstdio>
#include <string>
#include <vector>

#include "backends/cuda/runtime_kernel_headers.hpp"
#include "simulation/expression_transverser.hpp"


namespace {

// The compiler's messages for `source` with the kernels `kernels` (name expressions) instantiated,
// or "" when it compiles.
std::string compile(const std::string& source, const std::vector<std::string>& kernels = {}) {
    using structmd::kRuntimeKernelHeaderCount;
    using structmd::kRuntimeKernelHeaders;
    std::vector<const char*> names, texts;
    for (int h = 0; h < kRuntimeKernelHeaderCount; ++h) {
        names.push_back(kRuntimeKernelHeaders[h].name);
        texts.push_back(kRuntimeKernelHeaders[h].text);
    }
    nvrtcProgram program = nullptr;
    if (nvrtcCreateProgram(&program, source.c_str(), "header_check.cu", kRuntimeKernelHeaderCount, texts.data(),
                           names.data()) != NVRTC_SUCCESS)
        return "nvrtcCreateProgram failed";
    for (const std::string& kernel : kernels) nvrtcAddNameExpression(program, kernel.c_str());
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
        const std::string log = compile("#include \"" + header + "\"\n");
        if (log.empty()) continue;
        ++failed;
        std::printf("%s does not compile under NVRTC:\n%s\n", header.c_str(), log.c_str());
    }
    std::printf("%d of %d runtime kernel headers compile under NVRTC\n", structmd::kRuntimeKernelHeaderCount - failed,
                structmd::kRuntimeKernelHeaderCount);
    const structmd::ExpressionTransverserSpec spec = structmd::make_expression_transverser(
        "4 * (r^-12 - r^-6) + (r < 1.5) * mass_j + dx * charge_i", "compute", 2.5, -1);
    for (const char* real : {"float", "double"}) {
        const structmd::ExpressionSumKernels kernels = structmd::expression_sum_kernels(spec, real);
        const std::string log = compile(kernels.source, kernels.names);
        if (log.empty()) continue;
        ++failed;
        std::printf("the expression transverser's kernels in %s do not compile under NVRTC:\n%s\n", real, log.c_str());
    }
    return failed == 0 ? 0 : 1;
}
