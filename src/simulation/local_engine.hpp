#pragma once
// An engine on this process, as make_engine makes it: the simulation, its probes and what a view
// over ranks needs of it. Engine<B, R, PairR> (engine.hpp) is the one implementation.
#include "simulation/domain_member.hpp"
#include "simulation/simulation.hpp"
#include "simulation/simulation_probes.hpp"

namespace structmd {

class LocalEngine : public Simulation, public SimulationProbes, public DomainMember {
public:
    SimulationProbes& probes() final { return *this; }
};

}  // namespace structmd
