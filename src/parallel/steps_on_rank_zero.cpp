#include "parallel/steps_on_rank_zero.hpp"

#include <cstring>
#include <new>
#include <stdexcept>

#include "core/error.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

void StepsOnRankZero::send(const Request& request) {
    std::string bytes(sizeof(Op) + sizeof(int64_t) + sizeof(double), '\0');
    std::memcpy(&bytes[0], &request.op, sizeof(Op));
    std::memcpy(&bytes[sizeof(Op)], &request.number, sizeof(int64_t));
    std::memcpy(&bytes[sizeof(Op) + sizeof(int64_t)], &request.value, sizeof(double));
    bytes += request.text;
    comm_->broadcast(bytes, 0);
}

StepsOnRankZero::Request StepsOnRankZero::receive() {
    std::string bytes;
    comm_->broadcast(bytes, 0);
    Request request;
    const size_t head = sizeof(Op) + sizeof(int64_t) + sizeof(double);
    if (bytes.size() < head) throw Error(STRUCTMD_ERR_INTERNAL, "a malformed request from MPI rank 0");
    std::memcpy(&request.op, &bytes[0], sizeof(Op));
    std::memcpy(&request.number, &bytes[sizeof(Op)], sizeof(int64_t));
    std::memcpy(&request.value, &bytes[sizeof(Op) + sizeof(int64_t)], sizeof(double));
    request.text = bytes.substr(head);
    return request;
}

void StepsOnRankZero::announce(Op op, const std::string& text, int64_t number, double value) {
    if (driving_) send({op, number, value, text});
}

void StepsOnRankZero::fire(const std::vector<SimulationStep*>& due) {
    if (comm_->rank() != 0) {
        serve();
        return;
    }
    Request done;
    driving_ = true;
    try {
        for (SimulationStep* step : due) step->fire(*this);
        done.text = stopped_by();
    } catch (const Error& e) {
        done = {Op::failed, static_cast<int64_t>(e.status()), 0.0, e.what()};
    } catch (const std::bad_alloc&) {
        done = {Op::failed, static_cast<int64_t>(STRUCTMD_ERR_MEMORY), 0.0, "out of host memory"};
    } catch (const std::exception& e) {
        done = {Op::failed, static_cast<int64_t>(STRUCTMD_ERR_INTERNAL), 0.0,
                std::string("internal error, please report: ") + e.what()};
    }
    driving_ = false;
    send(done);
    if (done.op == Op::failed) throw Error(static_cast<structmd_status>(done.number), done.text);
}

void StepsOnRankZero::serve() {
    const auto n = static_cast<size_t>(particle_count());
    std::vector<double> scratch(9 * n), more(3 * n), most(3 * n);
    for (;;) {
        const Request request = receive();
        if (request.op == Op::done) {
            if (!request.text.empty()) request_stop(request.text);
            return;
        }
        // A gather that failed failed on every rank (run_together), rank 0 included: its steps stop
        // and it sends the failure, which ends the serving.
        if (request.op == Op::failed)
            throw Error(static_cast<structmd_status>(request.number), request.text + " (on MPI rank 0)");
        // A request this rank fails on fails on every rank, rank 0 included (its gathers run
        // together), which then sends the failure; this rank goes on serving until it does.
        try {
            serve_one(request, scratch, more, most);
        } catch (const std::exception&) {
        }
    }
}

void StepsOnRankZero::serve_one(const Request& request, std::vector<double>& scratch, std::vector<double>& more,
                                 std::vector<double>& most) {
    switch (request.op) {
        case Op::done:
        case Op::failed: break;
        case Op::compute: compute(static_cast<unsigned>(request.number)); break;
        case Op::read: read(static_cast<PerParticle>(request.number), scratch.data()); break;
        case Op::energy: energy(request.text); break;
        case Op::termArrays: term_energies_and_forces(request.text, scratch.data(), more.data(), most.data()); break;
        case Op::virial: virial(); break;
        case Op::setLambda: set_lambda(request.value); break;
        case Op::lambdaDerivative: lambda_derivative(); break;
    }
}

}  // namespace structmd
