#pragma once
// The device headers a kernel compiled at run time may include, embedded in the library by
// cmake/embed_headers.cmake (runtime_kernel_headers.cpp in the build tree), by include name.

namespace structmd {

struct RuntimeKernelHeader {
    const char* name;
    const char* text;
};
extern const RuntimeKernelHeader kRuntimeKernelHeaders[];
extern const int kRuntimeKernelHeaderCount;

}  // namespace structmd
