#pragma once
// Steps replayed as CUDA graphs. While a batch of steps is open, the backend records its launches
// (kernel, grid and argument bytes) instead of issuing them. At the end of the batch a sequence
// of the same kernels and grids as one seen before replays that graph, after updating the nodes
// whose arguments changed; a new sequence is built into a graph and kept for later batches.
// Anything that needs the device in between (a copy, a reduction, an allocation) first issues what
// was recorded, so the order of work never changes. Kernels read the step and time from the
// device clock, so the steps of a run pass the same arguments again and again and replaying a
// batch costs one graph launch.
//
// Launches recorded under a condition (a flag in device memory, see only_if) become the body of a
// conditional graph node, run only when the flag is set at that point of the graph: a step
// without a list build then launches none of the build's kernels. Issued outside a graph they run
// anyway, and their kernels test the flag themselves.
#include <cuda_runtime.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "backends/cuda/cuda_check.hpp"

namespace structmd {

// One launch of for_each_kernel(n, f) or for_each_lanes_kernel(n, lanes, f), held by value.
struct KernelLaunch {
    const void* kernel = nullptr;
    unsigned blocks = 0;
    unsigned threads = 0;
    bool withLanes = false;
    int64_t n = 0;
    int lanes = 1;
    std::string functor;  // the functor's bytes
    const int* condition = nullptr;  // runs only where *condition != 0 (null: always)
    bool opensCondition = false;     // the first launch of a conditional region
    void* params[3] = {nullptr, nullptr, nullptr};

    void** kernel_params() {
        params[0] = &n;
        if (withLanes) {
            params[1] = &lanes;
            params[2] = functor.data();
        } else {
            params[1] = functor.data();
        }
        return params;
    }
    cudaKernelNodeParams node_params() {
        cudaKernelNodeParams p{};
        p.func = const_cast<void*>(kernel);
        p.gridDim = dim3(blocks);
        p.blockDim = dim3(threads);
        p.kernelParams = kernel_params();
        return p;
    }
    bool same_arguments(const KernelLaunch& other) const {
        return n == other.n && lanes == other.lanes && functor == other.functor;
    }
    bool same_shape(const KernelLaunch& other) const {
        return kernel == other.kernel && blocks == other.blocks && threads == other.threads &&
               condition == other.condition && opensCondition == other.opensCondition;
    }
    void issue(cudaStream_t stream) {
        cuda_check(cudaLaunchKernel(kernel, dim3(blocks), dim3(threads), kernel_params(), 0, stream),
                   "launching a kernel");
    }
};

// Sets a conditional node's value from a flag the kernels before it wrote.
static __global__ void set_graph_condition(cudaGraphConditionalHandle handle, const int* flag) {
    cudaGraphSetConditional(handle, *flag != 0 ? 1u : 0u);
}

class StepGraphs {
public:
    StepGraphs() = default;
    StepGraphs(const StepGraphs&) = delete;
    StepGraphs& operator=(const StepGraphs&) = delete;
    ~StepGraphs() {
        for (Cached& c : cache_) release(c);
    }

    bool recording() const { return open_; }
    uint64_t captured() const { return captured_; }
    uint64_t replayed() const { return replayed_; }

    void open() {
        open_ = true;
        condition_ = nullptr;
        launches_.clear();
    }

    void record(KernelLaunch launch) {
        launch.condition = condition_;
        launch.opensCondition = condition_ && !conditionOpened_;
        conditionOpened_ = conditionOpened_ || condition_;
        launches_.push_back(std::move(launch));
    }

    // Launches recorded until end_condition run only where *flag != 0, evaluated once before the
    // first of them.
    void begin_condition(const int* flag) {
        condition_ = flag;
        conditionOpened_ = false;
    }
    void end_condition() { condition_ = nullptr; }

    // Issues what was recorded, one launch at a time, and goes on recording afresh.
    void flush(cudaStream_t stream) {
        for (KernelLaunch& launch : launches_) launch.issue(stream);
        launches_.clear();
    }

    // Ends the batch: replays the graph of these kernels, or builds one.
    void close(cudaStream_t stream) {
        open_ = false;
        if (launches_.empty()) return;
        Cached* graph = find();
        if (graph) {
            update(*graph);
            ++replayed_;
        } else {
            graph = &build();
            ++captured_;
        }
        graph->lastUse = ++uses_;
        launches_.clear();
        cuda_check(cudaGraphLaunch(graph->exec, stream), "launching a step graph");
    }

private:
    struct Cached {
        cudaGraph_t graph = nullptr;
        cudaGraphExec_t exec = nullptr;
        std::vector<cudaGraphNode_t> nodes;
        std::vector<KernelLaunch> launches;  // the arguments the nodes hold now
        uint64_t lastUse = 0;
    };
    static constexpr size_t kCacheSize = 4;  // a run needs two: full batches and the last, shorter one

    static void release(Cached& c) {
        if (c.exec) cudaGraphExecDestroy(c.exec);
        if (c.graph) cudaGraphDestroy(c.graph);
    }

    Cached* find() {
        for (Cached& c : cache_) {
            if (c.launches.size() != launches_.size()) continue;
            bool same = true;
            // Nodes inside a conditional body are not updated in place: their arguments must match.
            for (size_t k = 0; same && k < launches_.size(); ++k)
                same = c.launches[k].same_shape(launches_[k]) &&
                       (!launches_[k].condition || c.launches[k].same_arguments(launches_[k]));
            if (same) return &c;
        }
        return nullptr;
    }

    void update(Cached& c) {
        for (size_t k = 0; k < launches_.size(); ++k) {
            if (c.launches[k].same_arguments(launches_[k])) continue;
            const cudaKernelNodeParams params = launches_[k].node_params();
            cuda_check(cudaGraphExecKernelNodeSetParams(c.exec, c.nodes[k], &params), "updating a step graph");
            c.launches[k] = std::move(launches_[k]);
        }
    }

    Cached& build() {
        if (cache_.size() == kCacheSize) {
            size_t oldest = 0;
            for (size_t k = 1; k < cache_.size(); ++k)
                if (cache_[k].lastUse < cache_[oldest].lastUse) oldest = k;
            release(cache_[oldest]);
            cache_.erase(cache_.begin() + static_cast<std::ptrdiff_t>(oldest));
        }
        Cached c;
        cuda_check(cudaGraphCreate(&c.graph, 0), "creating a step graph");
        try {
            // The node the next one waits for, in the top graph and in the open conditional body,
            // and whether it is one of the recorded kernels (which the next may follow early).
            struct Tail {
                cudaGraphNode_t node = nullptr;
                bool kernel = false;
            };
            Tail last, lastInBody;
            cudaGraph_t body = nullptr;
            for (KernelLaunch& launch : launches_) {
                if (!launch.condition) body = nullptr;
                if (launch.opensCondition) {
                    body = add_conditional(c.graph, last.node, launch.condition);
                    last.kernel = false;
                    lastInBody = Tail{};
                }
                const cudaKernelNodeParams params = launch.node_params();
                cudaGraph_t graph = body ? body : c.graph;
                Tail& after = body ? lastInBody : last;
                cudaGraphNode_t node = nullptr;
                const bool early = after.kernel && follows_programmatically(launch.kernel);
                cuda_check(cudaGraphAddKernelNode(&node, graph, after.node && !early ? &after.node : nullptr,
                                                  after.node && !early ? 1 : 0, &params),
                           "building a step graph");
                if (early) {
                    // for_each kernels wait for this edge's source themselves (launch_kernels.cuh).
                    cudaGraphEdgeData edge{};
                    edge.from_port = cudaGraphKernelNodePortProgrammatic;
                    edge.type = cudaGraphDependencyTypeProgrammatic;
                    cuda_check(cudaGraphAddDependencies(graph, &after.node, &node, &edge, 1), "building a step graph");
                }
                after = Tail{node, true};
                c.nodes.push_back(node);
            }
            cuda_check(cudaGraphInstantiate(&c.exec, c.graph, 0), "instantiating a step graph");
        } catch (...) {
            release(c);
            throw;
        }
        c.launches = std::move(launches_);
        cache_.push_back(std::move(c));
        return cache_.back();
    }

    // Whether a kernel waits for the one before it itself (launch_kernels.cuh): compiled from PTX of
    // compute capability 9.0 or above and running on such a GPU. Kernels built for an older one (or
    // compiled at load time from its PTX) get a plain edge; so does a kernel whose attributes cannot
    // be read.
    bool follows_programmatically(const void* kernel) {
        auto known = programmatic_.find(kernel);
        if (known != programmatic_.end()) return known->second;
        cudaFuncAttributes attributes{};
        const bool waits = cudaFuncGetAttributes(&attributes, kernel) == cudaSuccess && attributes.ptxVersion >= 90 &&
                           attributes.binaryVersion >= 90;
        cudaGetLastError();  // a failed query leaves no error behind for the next check
        programmatic_.emplace(kernel, waits);
        return waits;
    }

    // Adds, after `last`, a kernel that reads *flag and an if-node on its value; `last` becomes the
    // if-node. Returns the graph of the if-node's body.
    static cudaGraph_t add_conditional(cudaGraph_t graph, cudaGraphNode_t& last, const int* flag) {
        cudaGraphConditionalHandle handle{};
        cuda_check(cudaGraphConditionalHandleCreate(&handle, graph, 0, 0), "creating a graph condition");
        void* args[2] = {&handle, &flag};
        cudaKernelNodeParams setter{};
        setter.func = reinterpret_cast<void*>(&set_graph_condition);
        setter.gridDim = dim3(1);
        setter.blockDim = dim3(1);
        setter.kernelParams = args;
        cudaGraphNode_t setNode = nullptr;
        cuda_check(cudaGraphAddKernelNode(&setNode, graph, last ? &last : nullptr, last ? 1 : 0, &setter),
                   "building a step graph");
        cudaGraphNodeParams ifNode{};
        ifNode.type = cudaGraphNodeTypeConditional;
        ifNode.conditional.handle = handle;
        ifNode.conditional.type = cudaGraphCondTypeIf;
        ifNode.conditional.size = 1;
        cuda_check(cudaGraphAddNode(&last, graph, &setNode, nullptr, 1, &ifNode), "building a step graph");
        return ifNode.conditional.phGraph_out[0];
    }

    bool open_ = false;
    const int* condition_ = nullptr;
    bool conditionOpened_ = false;
    std::vector<KernelLaunch> launches_;
    std::vector<Cached> cache_;
    std::unordered_map<const void*, bool> programmatic_;  // follows_programmatically, by kernel
    uint64_t uses_ = 0;
    uint64_t captured_ = 0;
    uint64_t replayed_ = 0;
};

}  // namespace structmd
