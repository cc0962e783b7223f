#pragma once
// The topology written beside a DCD trajectory, so that MDAnalysis (Universe("x.psf", "x.dcd")) and
// VMD (mol new x.psf; mol addfile x.dcd) read names, masses, charges and bonds with the positions:
// an X-PLOR/NAMD PSF, whitespace-separated ("NAMD" in its first line, the flag both readers take to
// split atom lines on blanks rather than read CHARMM's fixed columns; "EXT" for serials in fields of
// 10, the width VMD reads angles and dihedrals in).
//
//   PSF EXT NAMD
//   (blank)  2 !NTITLE, two REMARKS lines
//   N !NATOM, one line per particle of the frame, in the frame's order:
//     serial segment residue resname name type charge mass 0
//     serial = 1 + position in the frame (the DCD's atom index, also for a group's subset),
//     segment = "S" + the structure's chainId modulo 10^6 (S0 without it), residue = its resId
//     modulo 10^7 (1 without it): words of at most 7 characters, as VMD reads them,
//     resname UNK, name and type = the type's name cut to 7 characters (VMD reads at most 7),
//     blanks replaced by '_'; charge and mass the input's (0 for entries beyond the input's
//     particles, such as patches)
//   M !NBOND: bonds, four pairs of serials (each in 10 columns) a line; then !NTHETA: angles
//   (three triples a line) and !NPHI: dihedrals (two quadruples a line), each among the particles
//   of the frame only;
//   0 !NIMPHI, 0 !NDON, 0 !NACC, 0 !NNB: the sections readers expect to find, empty.
#include <string>

#include "steps/trajectory_writer.hpp"

namespace structmd {

// Writes `path` for the particles of `frame` (its ids, types and type names); throws Error(ERR_IO)
// starting with `owner` and naming the file when it cannot be written.
void write_psf_topology(const std::string& path, const std::string& owner, const TrajectoryFrame& frame,
                        const MoleculeLayout& molecules);

}  // namespace structmd
