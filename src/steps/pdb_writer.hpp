#pragma once
// The PDB trajectory: one MODEL per frame in PDB's fixed columns, with CONECT records for the bonds.
#include <memory>

#include "steps/trajectory_writer.hpp"

namespace structmd {

std::unique_ptr<TrajectoryWriter> make_pdb_writer(TrajectoryOptions options);

}  // namespace structmd
