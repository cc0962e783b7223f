#pragma once
// Kernels compiled at load time with NVRTC (part of the CUDA toolkit) from source that includes the
// engine's own device headers, so that a potential known only at run time (an expression) runs in
// the same traversal as a built-in one. The headers travel inside the library
// (runtime_kernel_headers.cpp, generated at build time): nothing is read from disk and no compiler
// is needed on the user's side. Plain C++: the engine's host code holds these without CUDA headers.
#include <string>
#include <vector>

namespace structmd {

class RuntimeKernels {
public:
    // Compiles `source` for the compute capability of `device` and loads the kernels named by
    // `kernels`, C++ name expressions such as "&structmd::for_each_kernel<Functor>". A source that
    // does not compile is an internal error carrying the compiler's log.
    RuntimeKernels(int device, const std::string& source, const std::vector<std::string>& kernels);
    ~RuntimeKernels();
    RuntimeKernels(const RuntimeKernels&) = delete;
    RuntimeKernels& operator=(const RuntimeKernels&) = delete;

    // The k-th kernel, launchable with cudaLaunchKernel and as a graph node.
    const void* kernel(size_t k) const { return kernels_.at(k); }
    // Wall time of compiling and loading, for the log.
    double seconds() const { return seconds_; }

private:
    void* library_ = nullptr;  // cudaLibrary_t
    std::vector<const void*> kernels_;
    double seconds_ = 0.0;
};

}  // namespace structmd
