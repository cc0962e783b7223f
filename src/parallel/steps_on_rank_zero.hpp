#pragma once
// The step-firing service of a simulation spread over the ranks of an MPI communicator (batches,
// batches_over_ranks.hpp, or spatial domains, domains_over_ranks.hpp): the view shows the whole
// system, and its simulation steps fire on rank 0 only, where they see it whole and write their files
// once. Meanwhile the other ranks serve what they ask (a request broadcast from rank 0 before each of
// the view's collective calls), until rank 0 says the steps are done, with the stop a flow-control
// step asked for or the failure of a step, which every rank then reports.
//
// A view derives from it, installs it as its local engine's StepFiring, and announces each
// collective getter it runs (announce(), a no-op unless rank 0 is firing steps). The serving ranks
// make the same calls on the view, so its getters need no more than being collective.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "parallel/communicator.hpp"
#include "simulation/domain_member.hpp"
#include "simulation/forwarding_simulation.hpp"

namespace structmd {

class StepsOnRankZero : public ForwardingSimulation, protected StepFiring {
protected:
    explicit StepsOnRankZero(std::shared_ptr<const Communicator> comm) : comm_(std::move(comm)) {}

    // What rank 0 asks the other ranks to take part in while the steps fire.
    enum class Op : int32_t {
        done,    // text: the step that asked to stop, or empty
        failed,  // number: the status, text: the message
        compute,     // number: the flags
        read,        // number: the PerParticle quantity
        energy,      // text: the term
        termArrays,  // text: the term
        virial,
        setLambda,  // value
        lambdaDerivative,
    };

    void fire(const std::vector<SimulationStep*>& due) override;
    // On rank 0 while the steps fire: tells the other ranks which collective call comes next.
    void announce(Op op, const std::string& text = std::string(), int64_t number = 0, double value = 0.0);
    // Rank 0, while the due steps fire.
    bool driving() const { return driving_; }

    std::shared_ptr<const Communicator> comm_;

private:
    struct Request {
        Op op = Op::done;
        int64_t number = 0;
        double value = 0.0;
        std::string text;
    };
    void serve();
    void serve_one(const Request& request, std::vector<double>& scratch, std::vector<double>& more,
                   std::vector<double>& most);
    void send(const Request& request);
    Request receive();

    bool driving_ = false;
};

}  // namespace structmd
