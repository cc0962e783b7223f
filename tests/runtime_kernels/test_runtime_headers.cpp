// Each device header that kernels compiled at run time may include (embedded in the library by
// cmake/embed_headers.cmake) compiles under NVRTC on its own. NVRTC refuses what nvcc accepts in
// these headers, a function without __host__ __device__ or the standard library, and the tests that
// would find out need a GPU; NVRTC itself needs none, so this runs wherever the CUDA toolkit is
// (scripts/build_cuda_check.sh runs it on the CI machine). The expression transverser's kernels, as the
// engine writes them (simulation/expression_transverser.hpp), are instantiated too: a template body
// (the lanes' combine, the traversals) is checked only where it is instantiated; so are the pair
// kernels of an expression potential, as CompiledPairInteraction names them (compiled_interaction.hpp),
// in every precision and choice of outputs. A functor's kResidentBlocks reaches the launch bounds of the
// kernels compiled for it (launch_kernels.cuh).
#include <nvrtc.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "backends/cuda/runtime_kernel_headers.hpp"
#include "simulation/expression_transverser.hpp"

namespace {

struct Compiled {
    std::string log;  // the compiler's messages, "" when it compiles
    std::string ptx;
};

// `source` with the kernels `kernels` (name expressions) instantiated.
Compiled compile(const std::string& source, const std::vector<std::string>& kernels = {}) {
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
        return {"nvrtcCreateProgram failed", ""};
    for (const std::string& kernel : kernels) nvrtcAddNameExpression(program, kernel.c_str());
    // A virtual architecture: no GPU is asked which one it is.
    const char* options[] = {"--std=c++17", "--gpu-architecture=compute_90"};
    const nvrtcResult result = nvrtcCompileProgram(program, 2, options);
    Compiled compiled;
    if (result != NVRTC_SUCCESS) {
        size_t size = 0;
        nvrtcGetProgramLogSize(program, &size);
        compiled.log.resize(size);
        nvrtcGetProgramLog(program, compiled.log.data());
        compiled.log = std::string(nvrtcGetErrorString(result)) + "\n" + compiled.log;
    } else {
        size_t size = 0;
        nvrtcGetPTXSize(program, &size);
        compiled.ptx.resize(size);
        nvrtcGetPTX(program, compiled.ptx.data());
    }
    nvrtcDestroyProgram(&program);
    return compiled;
}

// The blocks per multiprocessor that the PTX asks for the entry whose mangled name contains `name`,
// or -1 where it names none. Only an entry's own name, up to its '(', is matched: the name is also in
// the `// .globl` line ahead of the entry and in its parameters' names.
int resident_blocks(const std::string& ptx, const std::string& name) {
    size_t entry = ptx.find(".entry");
    while (entry != std::string::npos) {
        const size_t next = ptx.find(".entry", entry + 1);
        const std::string body = ptx.substr(entry, next == std::string::npos ? std::string::npos : next - entry);
        const size_t nameEnd = body.find('(');
        const size_t bound = body.find(".minnctapersm");
        if (body.substr(0, nameEnd).find(name) != std::string::npos && bound != std::string::npos)
            return std::atoi(body.c_str() + bound + std::string(".minnctapersm").size());
        entry = next;
    }
    return -1;
}

// Whether a functor naming kResidentBlocks gets them under both launches, and one naming none the
// launches' defaults.
int check_resident_blocks() {
    const Compiled compiled = compile(
        "#include \"backends/cuda/launch_kernels.cuh\"\n"
        "struct NamesFive { static constexpr int kResidentBlocks = 5;\n"
        "    __device__ void operator()(int64_t, structmd::Lanes) const {} };\n"
        "struct NamesNone { __device__ void operator()(int64_t, structmd::Lanes) const {} };\n",
        {"structmd::for_each_lanes_kernel<NamesFive>", "structmd::for_each_lone_lane_kernel<NamesFive>",
         "structmd::for_each_lanes_kernel<NamesNone>", "structmd::for_each_lone_lane_kernel<NamesNone>"});
    if (!compiled.log.empty()) {
        std::printf("the launches with a functor's resident blocks do not compile under NVRTC:\n%s\n",
                    compiled.log.c_str());
        return 1;
    }
    struct Expected {
        const char* entry;  // mangled: the launch, then the functor
        int blocks;
    };
    int failed = 0;
    for (const Expected expected : {Expected{"for_each_lanes_kernelI9NamesFive", 5},
                                    Expected{"for_each_lone_lane_kernelI9NamesFive", 5},
                                    Expected{"for_each_lanes_kernelI9NamesNone", 8},
                                    Expected{"for_each_lone_lane_kernelI9NamesNone", 12}}) {
        const int blocks = resident_blocks(compiled.ptx, expected.entry);
        std::printf("%s: %d resident blocks (expected %d)\n", expected.entry, blocks, expected.blocks);
        failed += blocks != expected.blocks;
    }
    return failed;
}

// The pair kernels of an expression potential (the engine's RuntimePotential over a Function of its
// own: r^-12 - r^-6), each precision and each choice of outputs, compile under NVRTC.
int check_pair_kernels() {
    const std::string source =
        "#include \"backends/cuda/launch_kernels.cuh\"\n#include \"forcefield/pair_kernel.hpp\"\n"
        "#include \"forcefield/expression_terms.hpp\"\n"
        "struct RuntimeExpression {\n"
        "    template <class R> struct Params { R columns[1]; };\n"
        "    template <class R> static SMD_HD SMD_INLINE void evaluate(const R* inputs, const Params<R>&, R* outputs) {\n"
        "        const R s6 = R(1) / (inputs[0] * inputs[0] * inputs[0] * inputs[0] * inputs[0] * inputs[0]);\n"
        "        outputs[0] = s6 * s6 - s6;\n"
        "        outputs[1] = (R(-12) * s6 * s6 + R(6) * s6) / inputs[0];\n"
        "    }\n"
        "};\n"
        "using RuntimePotential = structmd::ExpressionPair<RuntimeExpression>;\n";
    std::vector<std::string> kernels;
    for (const char* reals : {"float, float", "double, float", "double, double"})
        for (const char* outputs : {"true, false, false", "true, true, true", "false, true, false"})
            for (const char* launch : {"for_each_lanes_kernel", "for_each_lone_lane_kernel"})
                kernels.push_back(std::string("&structmd::") + launch + "<structmd::PairKernel<RuntimePotential, " + reals +
                                  ", " + outputs + ">>");
    const Compiled compiled = compile(source, kernels);
    if (compiled.log.empty()) return 0;
    std::printf("the pair kernels of an expression potential do not compile under NVRTC:\n%s\n", compiled.log.c_str());
    return 1;
}

}  // namespace

int main() {
    int failed = 0;
    for (int h = 0; h < structmd::kRuntimeKernelHeaderCount; ++h) {
        const std::string header = structmd::kRuntimeKernelHeaders[h].name;
        const std::string log = compile("#include \"" + header + "\"\n").log;
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
        const std::string log = compile(kernels.source, kernels.names).log;
        if (log.empty()) continue;
        ++failed;
        std::printf("the expression transverser's kernels in %s do not compile under NVRTC:\n%s\n", real, log.c_str());
    }
    failed += check_pair_kernels();
    failed += check_resident_blocks();
    return failed == 0 ? 0 : 1;
}
