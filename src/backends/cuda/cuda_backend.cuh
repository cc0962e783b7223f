#pragma once
// CUDA backend: device buffers and kernel launches on one stream per handle. Launches are
// asynchronous; the host waits only where a value must come back (a reduction, a read).
#include <cuda_runtime.h>
#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/mr/allocator.h>
#include <thrust/mr/disjoint_pool.h>
#include <thrust/mr/new.h>
#include <thrust/system/cuda/memory_resource.h>
#include <thrust/transform_reduce.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "backends/cuda/cuda_check.hpp"
#include "backends/cuda/launch_kernels.cuh"
#include "backends/cuda/pinned_staging.cuh"
#include "backends/cuda/runtime_compiler.hpp"
#include "backends/cuda/step_graphs.cuh"
#include "backends/backend_types.hpp"
#include "backends/transfer_counters.hpp"
#include "core/lanes.hpp"

namespace structmd {

template <class T>
class DeviceBuffer {
public:
    DeviceBuffer() = default;
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&& other) noexcept { swap(other); }
    DeviceBuffer& operator=(DeviceBuffer&& other) noexcept { swap(other); return *this; }
    ~DeviceBuffer() { release(); }

    T* data() { return data_; }
    const T* data() const { return data_; }
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    void resize(size_t n, MemoryAccount& account) {
        release();
        if (n > 0) {
            const cudaError_t status = cudaMalloc(&data_, n * sizeof(T));
            if (status != cudaSuccess) {
                cudaGetLastError();  // an allocation failure must not resurface at the next launch
                data_ = nullptr;
                cuda_check(status, ("allocating " + std::to_string(n * sizeof(T)) + " bytes of device memory").c_str());
            }
        }
        size_ = n;
        capacity_ = n;
        account_ = &account;
        account_->bytes += static_cast<int64_t>(n * sizeof(T));
    }
    // How many values the allocation has room for; set_size(n <= capacity()) keeps it and the
    // first n values.
    size_t capacity() const { return capacity_; }
    void set_size(size_t n) { size_ = n; }
    void release() {
        if (data_) cudaFree(data_);
        if (account_) account_->bytes -= static_cast<int64_t>(capacity_ * sizeof(T));
        data_ = nullptr;
        size_ = 0;
        capacity_ = 0;
    }
private:
    void swap(DeviceBuffer& other) noexcept {
        std::swap(data_, other.data_);
        std::swap(size_, other.size_);
        std::swap(capacity_, other.capacity_);
        std::swap(account_, other.account_);
    }
    T* data_ = nullptr;
    size_t size_ = 0;
    size_t capacity_ = 0;
    MemoryAccount* account_ = nullptr;
};

template <class T>
struct ReducePlus {
    __host__ __device__ T operator()(const T& a, const T& b) const { return a + b; }
};

struct ReduceMax {
    __host__ __device__ double operator()(double a, double b) const { return a > b ? a : b; }
};

template <class T>
struct FillFunctor {
    T* data;
    T value;
    __device__ void operator()(int64_t i) const { data[i] = value; }
};

template <class R>
class CudaFft3d;  // backends/cuda/cuda_fft.cuh, included where engines are instantiated (engines/)
template <class R>
class CudaCholesky;  // backends/cuda/cuda_cholesky.cuh, likewise

class CudaBackend : public BackendTypes<DeviceBuffer, PinnedStaging, CudaFft3d, CudaCholesky> {
public:
    static constexpr const char* name = "cuda";
    // Sorting every list in global memory at each build cut the LJ benchmark at a million particles
    // from 9.5e8 to 5.7e8 particle-steps/s on an H200; on the GPU a restart agrees with the
    // uninterrupted run to rounding instead.
    static constexpr bool ordered_neighbour_lists = false;
    // Cells as wide as the list radius where several lanes take a particle's candidates, a cell's
    // members in rounds; half as wide where a thread takes them alone (a million particles), which
    // then skips the cells out of the particle's reach (neighbour/cell_grid.hpp).
    int list_cell_reach(int64_t n) const { return lanes_for(n, LaneSizing::kFillDevice) == 1 ? 2 : 1; }

    explicit CudaBackend(int device) : device_(device) {
        int count = 0;
        if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0)
            throw Error(STRUCTMD_ERR_DEVICE, "backend \"cuda\": no usable GPU was found");
        if (device < 0 || device >= count)
            throw Error(STRUCTMD_ERR_ARGUMENT, "option \"device\": GPU " + std::to_string(device) +
                                                   " does not exist (found " + std::to_string(count) + ")");
        activate();
        cudaDeviceProp prop{};
        cuda_check(cudaGetDeviceProperties(&prop, device_), "reading device properties");
        deviceName_ = prop.name;
        residentThreads_ = static_cast<int64_t>(prop.multiProcessorCount) * prop.maxThreadsPerMultiProcessor;
        cuda_check(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "creating a stream");
    }
    CudaBackend(const CudaBackend&) = delete;
    CudaBackend& operator=(const CudaBackend&) = delete;
    ~CudaBackend() {
        if (stream_) cudaStreamDestroy(stream_);
    }

    int threads() const { return 0; }
    std::string device_name() const { return deviceName_; }
    void activate() const { cuda_check(cudaSetDevice(device_), "selecting the GPU"); }
    void synchronize() const {
        issue_recorded();
        cuda_check(cudaStreamSynchronize(stream_), "running on the GPU");
    }

    // The steps between begin_steps and end_steps run as CUDA graphs of kStepsPerGraph steps each
    // (step_graphs.cuh); begin_step opens the next graph when one is full.
    void begin_steps() const {
        graphs_.open();
        stepsInGraph_ = 0;
    }
    void begin_step() const {
        if (stepsInGraph_ == kStepsPerGraph) {
            graphs_.close(stream_);
            graphs_.open();
            stepsInGraph_ = 0;
        }
        ++stepsInGraph_;
    }
    void end_steps() const { graphs_.close(stream_); }
    // For work the host launches itself (a device force callback): what was recorded is issued
    // first, so the host's kernels run in order on the engine's stream.
    void* host_launch_stream() const {
        issue_recorded();
        return stream_;
    }
    int device_ordinal() const { return device_; }
    uint64_t graphs_captured() const { return graphs_.captured(); }
    uint64_t graphs_replayed() const { return graphs_.replayed(); }

    template <class F>
    void for_each(int64_t n, const F& f) const {
        if (n <= 0) return;
        const Grid grid = grid_for(n, 1);
        if (!graphs_.recording()) {
            for_each_kernel<<<grid.blocks, kThreads, 0, stream_>>>(n, f);
            cuda_check(cudaGetLastError(), "launching a kernel");
            return;
        }
        graphs_.record(recorded(reinterpret_cast<const void*>(&for_each_kernel<F>), grid, false, n, f));
    }

    // f(i, lanes) for i < n, with lanes (up to a warp) sized by `sizing` (core/lanes.hpp): a list
    // build over 10,000 particles runs 32 threads per particle, their pair kernel 8, and either runs
    // one thread per particle at a million.
    // Lanes of one particle read its entries side by side; single threads of consecutive particles
    // read entry k of each side by side. The pair kernels read the lists, so their lanes decide.
    bool lists_by_rows(int64_t n) const { return lanes_for(n, LaneSizing::kNeighbourSum) > 1; }
    // The list builds write each entry with its pair's cells' offset where the list keeps cell-local
    // positions (NeighbourView::entryShift), so the mixed-precision pair kernels skip the cells' codes.
    bool list_entries_carry_cells() const { return true; }

    int lanes_for(int64_t n, LaneSizing sizing) const {
        int lanes = 1;
        if (sizing == LaneSizing::kWarp)
            lanes = 32;
        else if (sizing == LaneSizing::kFillDevice)
            while (lanes < 32 && n * lanes < residentThreads_) lanes *= 2;
        else
            while (lanes < 32 && 2 * n * lanes <= residentThreads_ / 2) lanes *= 2;
        return lanes;
    }

    template <class F>
    void for_each_lanes(int64_t n, const F& f, LaneSizing sizing = LaneSizing::kNeighbourSum) const {
        if (n <= 0) return;
        const Grid grid = grid_for(n, lanes_for(n, sizing));
        auto* kernel = grid.lanes == 1 ? &for_each_lone_lane_kernel<F> : &for_each_lanes_kernel<F>;
        if (!graphs_.recording()) {
            kernel<<<grid.blocks, kThreads, 0, stream_>>>(n, grid.lanes, f);
            cuda_check(cudaGetLastError(), "launching a kernel");
            return;
        }
        graphs_.record(recorded(reinterpret_cast<const void*>(kernel), grid, true, n, f));
    }

    // Runs the launches of body only while the flag in device memory is set when they are reached.
    // Inside a step graph they become a conditional node; issued directly they run, and each of
    // their kernels must test the flag itself.
    template <class Body>
    void only_if(const int* flag, Body&& body) const {
        if (!graphs_.recording()) {
            body();
            return;
        }
        graphs_.begin_condition(flag);
        try {
            body();
        } catch (...) {
            graphs_.end_condition();
            throw;
        }
        graphs_.end_condition();
    }

    // Kernels compiled at load time (runtime_compiler.hpp) for this handle's GPU.
    static constexpr bool compiles_at_run_time = true;
    using CompiledKernels = std::shared_ptr<const RuntimeKernels>;
    std::shared_ptr<const RuntimeKernels> compile(const std::string& source, const std::vector<std::string>& kernels) const {
        activate();
        return std::make_shared<const RuntimeKernels>(device_, source, kernels);
    }

    // for_each(n, f) and for_each_lanes(n, f) (sized for a neighbour sum) through `kernel`, a for_each_kernel or
    // for_each_lanes_kernel compiled at run time whose functor has the layout of F.
    template <class F>
    void for_each_compiled(const void* kernel, int64_t n, const F& f) const {
        if (n > 0) launch(recorded(kernel, grid_for(n, 1), false, n, f));
    }
    template <class F>
    void for_each_lanes_compiled(const void* kernel, int64_t n, const F& f) const {
        if (n > 0) launch(recorded(kernel, grid_for(n, lanes_for(n, LaneSizing::kNeighbourSum)), true, n, f));
    }

    template <class T, class F>
    T reduce(int64_t n, const F& f, T zero) const {
        if (n <= 0) return zero;
        issue_recorded();
        transfers_.deviceToHost += sizeof(T);
        return thrust::transform_reduce(thrust::cuda::par(temporaryAllocator_).on(stream_),
                                        thrust::counting_iterator<int64_t>(0),
                                        thrust::counting_iterator<int64_t>(n), f, zero, ReducePlus<T>());
    }

    // Largest f(i) over i < n (0 for n = 0; f is meant to be non-negative).
    template <class F>
    double maximum(int64_t n, const F& f) const {
        if (n <= 0) return 0.0;
        issue_recorded();
        transfers_.deviceToHost += sizeof(double);
        return thrust::transform_reduce(thrust::cuda::par(temporaryAllocator_).on(stream_),
                                        thrust::counting_iterator<int64_t>(0),
                                        thrust::counting_iterator<int64_t>(n), f, 0.0, ReduceMax());
    }

    // The i < n for which keep(i) holds, in increasing order, into out (room for n); returns how many.
    template <class Keep>
    int64_t select(int64_t n, const Keep& keep, int64_t* out) const {
        if (n <= 0) return 0;
        issue_recorded();
        transfers_.deviceToHost += sizeof(int64_t);
        return thrust::copy_if(thrust::cuda::par(temporaryAllocator_).on(stream_),
                               thrust::counting_iterator<int64_t>(0),
                               thrust::counting_iterator<int64_t>(n), out, keep) - out;
    }

    // Buffers are sized through their backend, which keeps the account of what they hold.
    template <class T>
    void resize(Buffer<T>& buffer, size_t n) const {
        if (n == buffer.size()) return;
        issue_recorded();  // recorded kernels may still use the old allocation
        buffer.resize(n, memory_);
    }

    // Sizes a buffer for n values in the allocation it has while that has room, keeping the
    // values; otherwise allocates n, or an eighth more when it grows a buffer that had values
    // (values unspecified). For arrays whose length changes a little and often (a spatial domain's
    // slots), at no cost to one whose length is set once.
    template <class T>
    void fit(Buffer<T>& buffer, size_t n) const {
        if (n > buffer.capacity()) {
            issue_recorded();  // recorded kernels may still use the old allocation
            buffer.resize(buffer.capacity() == 0 ? n : n + n / 8, memory_);
        }
        buffer.set_size(n);
    }

    template <class T>
    void fill(Buffer<T>& buffer, const T& value) const {
        for_each(static_cast<int64_t>(buffer.size()), FillFunctor<T>{buffer.data(), value});
    }

    // Copies are ordered on the handle's stream, after the kernels queued before them.
    template <class T>
    void upload(Buffer<T>& buffer, const T* host, size_t n) const {
        resize(buffer, n);
        if (n == 0) return;
        transfers_.hostToDevice += n * sizeof(T);
        issue_recorded();
        cuda_check(cudaMemcpyAsync(buffer.data(), host, n * sizeof(T), cudaMemcpyHostToDevice, stream_),
                   "copying to the device");
        synchronize();
    }

    template <class T>
    void download(const Buffer<T>& buffer, T* host, size_t n) const {
        if (n == 0) return;
        transfers_.deviceToHost += n * sizeof(T);
        issue_recorded();
        cuda_check(cudaMemcpyAsync(host, buffer.data(), n * sizeof(T), cudaMemcpyDeviceToHost, stream_),
                   "copying from the device");
        synchronize();
    }

    // From pinned staging: queued on the stream, and the host goes on at once (host.reserve waits
    // before the staging is written again).
    template <class T>
    void upload(Buffer<T>& buffer, Staging<T>& host, size_t n) const {
        resize(buffer, n);
        if (n == 0) return;
        transfers_.hostToDevice += n * sizeof(T);
        issue_recorded();
        cuda_check(cudaMemcpyAsync(buffer.data(), host.data(), n * sizeof(T), cudaMemcpyHostToDevice, stream_),
                   "copying to the device");
        host.mark_read_by(stream_);
    }

    // Kernels queued since read n values from the staging directly (its pointer is the device's
    // too): counted as copied, and kept until they are done. Launches a step graph still holds are
    // issued first, or the event would pass before they read and the host could overwrite the values.
    template <class T>
    void read_from_host(Staging<T>& host, size_t n) const {
        transfers_.hostToDevice += n * sizeof(T);
        issue_recorded();
        host.mark_read_by(stream_);
    }

    // Kernels queued since wrote n values into the staging directly: counted as copied. They are
    // there once the stream has been waited for: at once with wait_for_writes_to_host.
    template <class T>
    void written_to_host(const Staging<T>&, size_t n) const {
        transfers_.deviceToHost += n * sizeof(T);
    }
    template <class T>
    void wait_for_writes_to_host(const Staging<T>& host, size_t n) const {
        written_to_host(host, n);
        synchronize();
    }

    // Into pinned staging; the values are there when this returns.
    template <class T>
    const T* download(const Buffer<T>& buffer, Staging<T>& host, size_t n) const {
        T* values = host.reserve(n);
        download(buffer, values, n);
        return values;
    }

    template <class T>
    T read(const Buffer<T>& buffer, size_t index) const {
        transfers_.deviceToHost += sizeof(T);
        // Into pinned memory: a copy to pageable memory is staged by the driver, which costs a step
        // call (it reads the fault flag) several microseconds more.
        auto* value = reinterpret_cast<T*>(
            scalar_.reserve((sizeof(T) + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t)));
        issue_recorded();
        cuda_check(cudaMemcpyAsync(value, buffer.data() + index, sizeof(T), cudaMemcpyDeviceToHost, stream_),
                   "reading from the device");
        synchronize();
        return *value;
    }

    // Sets one element from a kernel, so that no host synchronisation is needed.
    template <class T>
    void write(Buffer<T>& buffer, size_t index, const T& value) const {
        for_each(1, FillFunctor<T>{buffer.data() + index, value});
    }

    const TransferCounters& transfers() const { return transfers_; }
    int64_t memory_bytes() const { return memory_.bytes; }

private:
    // Enough steps to make the launch of a graph negligible, few enough that the graph stays small
    // and the last, shorter batch of a call is cheap to capture.
    static constexpr int kStepsPerGraph = 16;

    void issue_recorded() const {
        if (graphs_.recording()) graphs_.flush(stream_);
    }

    static constexpr unsigned kThreads = kBlockThreads;
    struct Grid {
        unsigned blocks;
        int lanes;
    };
    static Grid grid_for(int64_t n, int lanes) {
        return {static_cast<unsigned>((n * lanes + kThreads - 1) / kThreads), lanes};
    }

    template <class F>
    static KernelLaunch recorded(const void* kernel, Grid grid, bool withLanes, int64_t n, const F& f) {
        KernelLaunch launch;
        launch.kernel = kernel;
        launch.blocks = grid.blocks;
        launch.threads = kThreads;
        launch.withLanes = withLanes;
        launch.n = n;
        launch.lanes = grid.lanes;
        // Padding bytes hold whatever the stack held: cleared, so that equal functors compare
        // equal and a replayed graph keeps its nodes (those in conditional bodies must match).
        F copy = f;
#if defined(__has_builtin)
#if __has_builtin(__builtin_clear_padding)
        __builtin_clear_padding(&copy);
#endif
#endif
        launch.functor.assign(reinterpret_cast<const char*>(&copy), sizeof(F));
        return launch;
    }

    void launch(KernelLaunch&& kernel) const {
        if (graphs_.recording())
            graphs_.record(std::move(kernel));
        else
            kernel.issue(stream_);
    }

    int device_;
    mutable StepGraphs graphs_;
    mutable int stepsInGraph_ = 0;
    mutable TransferCounters transfers_;
    mutable MemoryAccount memory_;
    mutable PinnedStaging<std::max_align_t> scalar_;  // where read() lands
    int64_t residentThreads_ = 0;  // threads the device holds at once
    std::string deviceName_;
    cudaStream_t stream_ = nullptr;
    // Temporary storage of thrust's reductions and selections, kept from one call to the next:
    // thrust would otherwise allocate and free it in every call (cudaFree waits for the whole GPU),
    // as a spatial domain does every step (its move check) and at every rebuild (the selections).
    using TemporaryPool = thrust::mr::disjoint_unsynchronized_pool_resource<thrust::system::cuda::memory_resource,
                                                                             thrust::mr::new_delete_resource>;
    mutable thrust::system::cuda::memory_resource deviceMemory_;
    mutable thrust::mr::new_delete_resource bookkeeping_;
    mutable TemporaryPool temporaries_{&deviceMemory_, &bookkeeping_};
    mutable thrust::mr::allocator<char, TemporaryPool> temporaryAllocator_{&temporaries_};
};

}  // namespace structmd
