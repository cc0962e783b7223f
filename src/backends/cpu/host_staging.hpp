#pragma once
// The CPU backend's counterpart of the CUDA backend's pinned staging: plain host memory, reused call
// after call, so that the engine packs, unpacks, gathers into and scatters from it the same way on
// both backends.
#include <cstddef>
#include <vector>

namespace structmd {

template <class T>
class HostStaging {
public:
    T* reserve(size_t n) {
        if (values_.size() < n) values_.resize(n);
        return values_.data();
    }
    T* data() { return values_.data(); }
    const T* data() const { return values_.data(); }

private:
    std::vector<T> values_;
};

}  // namespace structmd
