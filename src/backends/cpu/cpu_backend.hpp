#pragma once
// CPU backend: buffers in host memory and loops over OpenMP threads. It runs the very functors the
// CUDA backend launches as kernels.
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "backends/cpu/host_staging.hpp"
#include "backends/backend_types.hpp"
#include "backends/transfer_counters.hpp"
#include "core/lanes.hpp"

namespace structmd {

template <class T>
class HostBuffer {
public:
    HostBuffer() = default;

    T* data() { return data_.data(); }
    const T* data() const { return data_.data(); }
    size_t size() const { return data_.size(); }
    bool empty() const { return data_.empty(); }
    // Contents are unspecified after a resize, as for a device buffer.
    void resize(size_t n, MemoryAccount& account) {
        release();
        data_.resize(n);
        held_ = n;
        account_ = &account;
        account_->bytes += static_cast<int64_t>(n * sizeof(T));
    }
    // How many values the allocation has room for; set_size(n <= capacity()) keeps it and the
    // first n values.
    size_t capacity() const { return held_; }
    void set_size(size_t n) { data_.resize(n); }
    void release() {
        if (account_) account_->bytes -= static_cast<int64_t>(held_ * sizeof(T));
        std::vector<T>().swap(data_);
        held_ = 0;
    }
    HostBuffer(const HostBuffer&) = delete;
    HostBuffer& operator=(const HostBuffer&) = delete;
    HostBuffer(HostBuffer&& other) noexcept { swap(other); }
    HostBuffer& operator=(HostBuffer&& other) noexcept { swap(other); return *this; }
    ~HostBuffer() { release(); }

private:
    void swap(HostBuffer& other) noexcept {
        data_.swap(other.data_);
        std::swap(held_, other.held_);
        std::swap(account_, other.account_);
    }
    std::vector<T> data_;
    size_t held_ = 0;  // the allocation's room, as resize made it
    MemoryAccount* account_ = nullptr;
};

// Whether a functor offers a loop of its own for the host: host_rows(begin, end) does items
// begin .. end - 1 on the calling thread (the pair kernel and the list build, which arrange their
// work for a CPU core's caches and vector units).
template <class F, class = void>
struct has_host_rows : std::false_type {};
template <class F>
struct has_host_rows<F, std::void_t<decltype(std::declval<const F&>().host_rows(int64_t(), int64_t()))>>
    : std::true_type {};

template <class R>
class CpuFft3d;  // backends/cpu/cpu_fft.hpp, included where engines are instantiated (engines/)
template <class R>
class CpuCholesky;  // backends/cpu/cpu_cholesky.hpp, likewise

class CpuBackend : public BackendTypes<HostBuffer, HostStaging, CpuFft3d, CpuCholesky> {
public:
    static constexpr const char* name = "cpu";
    // Neighbour lists in index order: force sums independent of the build history, so a restart
    // continues bit for bit (the promise of the CPU backend).
    static constexpr bool ordered_neighbour_lists = true;
    // Cells half the list radius wide: a core skips the candidates out of a particle's reach
    // (neighbour/cell_grid.hpp).
    int list_cell_reach(int64_t) const { return 2; }

    explicit CpuBackend(int threads) : threads_(threads > 0 ? threads : omp_get_max_threads()) {}

    int threads() const { return threads_; }
    std::string device_name() const { return "host CPU"; }
    void activate() const {}
    void synchronize() const {}
    // Steps run as they are issued: there are no launches to replay.
    void begin_steps() const {}
    void begin_step() const {}
    void end_steps() const {}
    void* host_launch_stream() const { return nullptr; }  // host memory: no stream to order work on
    int device_ordinal() const { return -1; }             // host memory
    uint64_t graphs_captured() const { return 0; }
    uint64_t graphs_replayed() const { return 0; }

    // Every kernel is compiled with the library: a potential known only at run time is interpreted.
    static constexpr bool compiles_at_run_time = false;

    // Loops shorter than this run on the calling thread: waking a team costs more than they do.
    static constexpr int64_t kParallelThreshold = 2048;

    template <class F>
    void for_each(int64_t n, const F& f) const {
#pragma omp parallel for num_threads(threads_) schedule(static) if (n >= kParallelThreshold)
        for (int64_t i = 0; i < n; ++i) f(i);
    }

    // Runs the launches of body only while the flag in backend memory is set. Work runs as it is
    // issued here, so the flag already holds what the launches before set.
    template <class Body>
    void only_if(const int* flag, Body&& body) const {
        if (*flag) body();
    }

    // A thread reads a particle's neighbours one after the other: side by side suits its cache.
    bool lists_by_rows(int64_t) const { return true; }
    // host_rows writes slots alone, and its pair loop (PairRowsOnHost) reads the cells' codes.
    bool list_entries_carry_cells() const { return false; }

    // f(i, lanes) for i < n, one lane per item: a CPU thread works through a neighbour loop alone.
    // A functor with a host loop of its own gets one contiguous range of items a thread.
    template <class F>
    void for_each_lanes(int64_t n, const F& f, LaneSizing = LaneSizing::kNeighbourSum) const {
        if constexpr (has_host_rows<F>::value) {
            const int teams = n >= kParallelThreshold ? threads_ : 1;
#pragma omp parallel num_threads(teams) if (teams > 1)
            {
                const int64_t team = omp_get_thread_num(), size = omp_get_num_threads();
                f.host_rows(n * team / size, n * (team + 1) / size);
            }
        } else {
            for_each(n, [&](int64_t i) { f(i, Lanes{}); });
        }
    }

    // Sum of f(i) over i < n. Partial sums over fixed blocks make the result independent of the
    // thread count, so a run is reproducible bit for bit on any number of threads.
    template <class T, class F>
    T reduce(int64_t n, const F& f, T zero) const {
        constexpr int64_t block = 4096;
        const int64_t blocks = (n + block - 1) / block;
        std::vector<T> partial(static_cast<size_t>(blocks), zero);
#pragma omp parallel for num_threads(threads_) schedule(static) if (n >= kParallelThreshold)
        for (int64_t b = 0; b < blocks; ++b) {
            T sum = zero;
            const int64_t end = std::min(n, (b + 1) * block);
            for (int64_t i = b * block; i < end; ++i) sum = sum + f(i);
            partial[b] = sum;
        }
        T total = zero;
        for (const T& p : partial) total = total + p;
        transfers_.deviceToHost += sizeof(T);
        return total;
    }

    // Largest f(i) over i < n (0 for n = 0; f is meant to be non-negative).
    template <class F>
    double maximum(int64_t n, const F& f) const {
        double largest = 0.0;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(max : largest) if (n >= kParallelThreshold)
        for (int64_t i = 0; i < n; ++i) largest = std::max(largest, static_cast<double>(f(i)));
        transfers_.deviceToHost += sizeof(double);
        return largest;
    }

    // The i < n for which keep(i) holds, in increasing order, into out (room for n); returns how many.
    template <class Keep>
    int64_t select(int64_t n, const Keep& keep, int64_t* out) const {
        int64_t count = 0;
        for (int64_t i = 0; i < n; ++i)
            if (keep(i)) out[count++] = i;
        transfers_.deviceToHost += sizeof(int64_t);
        return count;
    }

    // Buffers are sized through their backend, which keeps the account of what they hold.
    template <class T>
    void resize(Buffer<T>& buffer, size_t n) const {
        if (n != buffer.size()) buffer.resize(n, memory_);
    }

    // Sizes a buffer for n values in the allocation it has while that has room, keeping the
    // values; otherwise allocates n, or an eighth more when it grows a buffer that had values
    // (values unspecified). For arrays whose length changes a little and often (a spatial domain's
    // slots), at no cost to one whose length is set once.
    template <class T>
    void fit(Buffer<T>& buffer, size_t n) const {
        if (n > buffer.capacity()) buffer.resize(buffer.capacity() == 0 ? n : n + n / 8, memory_);
        buffer.set_size(n);
    }

    template <class T>
    void fill(Buffer<T>& buffer, const T& value) const {
        T* data = buffer.data();
        for_each(static_cast<int64_t>(buffer.size()), [=](int64_t i) { data[i] = value; });
    }

    template <class T>
    void upload(Buffer<T>& buffer, const T* host, size_t n) const {
        transfers_.hostToDevice += n * sizeof(T);
        resize(buffer, n);
        std::copy(host, host + n, buffer.data());
    }

    template <class T>
    void download(const Buffer<T>& buffer, T* host, size_t n) const {
        transfers_.deviceToHost += n * sizeof(T);
        std::copy(buffer.data(), buffer.data() + n, host);
    }

    // Through the backend's staging, as on CUDA (where the upload is asynchronous).
    template <class T>
    void upload(Buffer<T>& buffer, Staging<T>& host, size_t n) const {
        upload(buffer, host.data(), n);
    }

    template <class T>
    const T* download(const Buffer<T>& buffer, Staging<T>& host, size_t n) const {
        T* values = host.reserve(n);
        download(buffer, values, n);
        return values;
    }

    // The loops that read or wrote the staging have run: only the account of the bytes is kept.
    template <class T>
    void read_from_host(Staging<T>&, size_t n) const {
        transfers_.hostToDevice += n * sizeof(T);
    }

    template <class T>
    void written_to_host(const Staging<T>&, size_t n) const {
        transfers_.deviceToHost += n * sizeof(T);
    }
    template <class T>
    void wait_for_writes_to_host(const Staging<T>& host, size_t n) const {
        written_to_host(host, n);
    }

    template <class T>
    T read(const Buffer<T>& buffer, size_t index) const {
        transfers_.deviceToHost += sizeof(T);
        return buffer.data()[index];
    }

    template <class T>
    void write(Buffer<T>& buffer, size_t index, const T& value) const {
        buffer.data()[index] = value;
    }

    const TransferCounters& transfers() const { return transfers_; }
    int64_t memory_bytes() const { return memory_.bytes; }

private:
    int threads_;
    mutable TransferCounters transfers_;
    mutable MemoryAccount memory_;
};

}  // namespace structmd
