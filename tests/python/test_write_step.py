"""["WriteStep","WriteStep"]: every output format is read back here by a reader written from the
format's published description (not from structmd's writer), and compared with the positions the
API gives at the same steps. Unwrapped reference positions are rebuilt here from the wrapped ones by
following each particle through the boundary, so pbc=false is checked against an independent unwrap."""

import shutil
import struct
import subprocess

import numpy as np
import pytest

import structmd

BOX = np.array([8.0, 9.0, 10.0])  # unequal edges, so a swapped axis shows
TIME_STEP = 0.005
STEPS = 13                         # frames at 0, 3, 6, 9, 12, and the final state at 13
INTERVAL = 3
# A name longer than PDB's 4 columns, and an element symbol among coarse-grained names.
TYPES = [["A", 1.0, 0.5, 0.0], ["Polymer", 2.0, 0.7, 0.0], ["Na", 1.5, 0.6, 0.0]]
ELEMENTS = {"Na": 11}  # of the names above
FORMATS = ["xyz", "sp", "lammpstrj", "dcd", "pdb"]


def initial_state():
    """20 particles on a 3x3x3 grid of the box, moving; those on the +x face move out through it
    and those on the -y face out through that one, so the run crosses the boundary both ways."""
    rng = np.random.default_rng(2024)
    spacing = BOX / 3
    sites = []
    for i in range(3):
        for j in range(3):
            for k in range(3):
                sites.append([BOX[0] / 2 - 0.05 - (2 - i) * spacing[0],
                              -BOX[1] / 2 + 0.05 + j * spacing[1],
                              (k - 1) * spacing[2]])
    positions = np.array(sites[:20])
    velocities = rng.normal(0.0, 1.5, positions.shape)
    on_plus_x = positions[:, 0] > BOX[0] / 2 - 0.1
    on_minus_y = positions[:, 1] < -BOX[1] / 2 + 0.1
    velocities[on_plus_x, 0] = np.abs(velocities[on_plus_x, 0]) + 2.0
    velocities[on_minus_y, 1] = -np.abs(velocities[on_minus_y, 1]) - 2.0
    types = [TYPES[i % len(TYPES)][0] for i in range(len(positions))]
    return positions, velocities, types


def document(writers, current_step=0, steps=STEPS):
    positions, velocities, types = initial_state()
    return {
        "system": {"info": {"type": ["Simulation", "Information"], "parameters": {"name": "write"}}},
        "global": {
            "types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"], "data": TYPES},
            "ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"],
                         "data": [[BOX.tolist(), 1.0]]},
            "fundamental": {"type": ["Fundamental", "Time"], "parameters": {"currentStep": current_step}},
        },
        "integrator": {
            "vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": TIME_STEP}},
            "schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],
                         "data": [[1, "vv", steps]]},
        },
        "state": {"labels": ["id", "position", "velocity"],
                  "data": [[i, p.tolist(), v.tolist()] for i, (p, v) in enumerate(zip(positions, velocities))]},
        "topology": {
            "structure": {"labels": ["id", "type"], "data": [[i, t] for i, t in enumerate(types)]},
            "forceField": {
                "nl": {"type": ["VerletConditionalListSet", "all"]},
                "lj": {"type": ["NonBonded", "LennardJonesType1"],
                       "parameters": {"cutOffFactor": 2.5, "condition": "all"},
                       "labels": ["name_i", "name_j", "epsilon", "sigma"],
                       "data": [["A", "A", 1.0, 1.0], ["A", "Polymer", 1.0, 1.0], ["Polymer", "Polymer", 1.0, 1.0]]},
            },
        },
        "simulationStep": writers,
    }


def writer(path, output_format, **parameters):
    entry = {"intervalStep": INTERVAL, "outputFilePath": str(path), "outputFormat": output_format}
    entry.update(parameters)
    return {"type": ["WriteStep", "WriteStep"], "parameters": entry}


def minimum_image(d):
    return d - BOX * np.round(d / BOX)


def run_and_record(sim, doc, motion=False):
    """Steps one at a time; {step: (wrapped, unwrapped)} for every step, the final one included, and
    with motion=True each step's velocities and forces too: {step: (wrapped, unwrapped, v, F)}."""
    sim.load(doc)
    extra = lambda: (np.asarray(sim.velocities), np.asarray(sim.forces)) if motion else ()
    wrapped = np.asarray(sim.positions)
    unwrapped = wrapped.copy()  # the initial positions lie inside the box
    record = {sim.step_number: (wrapped, unwrapped) + extra()}
    last = sim.info["final_step"]
    while sim.step_number < last:
        sim.step(1)
        now = np.asarray(sim.positions)
        unwrapped = unwrapped + minimum_image(now - wrapped)
        wrapped = now
        record[sim.step_number] = (wrapped, unwrapped) + extra()
    return record


def written_steps(first, last):
    """The steps the writer fires at: multiples of the interval, and the final state."""
    steps = [s for s in range(first, last) if s % INTERVAL == 0]
    return steps + [last]


# ---- readers, from the formats' published descriptions ------------------------------------------

def read_xyz(path):
    lines = path.read_text().splitlines()
    frames, k = [], 0
    while k < len(lines):
        n = int(lines[k])
        comment = lines[k + 1]
        fields = dict(item.split("=", 1) for item in comment.replace('"', "").split(" ") if "=" in item)
        atoms = [line.split() for line in lines[k + 2:k + 2 + n]]
        frames.append({"step": int(fields["step"]), "comment": comment, "names": [a[0] for a in atoms],
                       "xyz": np.array([[float(v) for v in a[1:4]] for a in atoms]),
                       "Z": [int(a[4]) for a in atoms], "type": [int(a[5]) for a in atoms]})
        k += 2 + n
    return frames


def read_sp(path):
    frames = []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            half = [float(part.split("=")[1]) for part in line[1:].split(";") if part]
            frames.append({"half_box": np.array(half), "rows": []})
        else:
            frames[-1]["rows"].append([float(v) for v in line.split()])
    for frame in frames:
        rows = np.array(frame["rows"])
        frame.update(rows=rows, xyz=rows[:, :3], radius=rows[:, 3], type=rows[:, 4])
    return frames


def read_lammpstrj(path):
    lines = path.read_text().splitlines()
    frames, k = [], 0
    while k < len(lines):
        assert lines[k] == "ITEM: TIMESTEP"
        step = int(lines[k + 1])
        assert lines[k + 2] == "ITEM: NUMBER OF ATOMS"
        n = int(lines[k + 3])
        assert lines[k + 4] == "ITEM: BOX BOUNDS pp pp pp"
        bounds = np.array([[float(v) for v in lines[k + 5 + d].split()] for d in range(3)])
        columns = lines[k + 8].split()[2:]
        assert lines[k + 8].startswith("ITEM: ATOMS ")
        table = np.array([[float(v) for v in line.split()] for line in lines[k + 9:k + 9 + n]])
        frames.append({"step": step, "bounds": bounds, "columns": columns,
                       "id": table[:, 0].astype(int), "type": table[:, 1].astype(int), "xyz": table[:, 2:5]})
        k += 9 + n
    return frames


def read_pdb(path):
    """Fixed columns: ATOM serial 7-11, name 13-16, x 31-38, y 39-46, z 47-54; CRYST1 a b c 7-33,
    angles 34-54, space group 56-66."""
    frames = []
    for line in path.read_text().splitlines():
        if line.startswith("MODEL "):
            frames.append({"model": int(line[10:14]), "serial": [], "name": [], "xyz": []})
        elif line.startswith("CRYST1"):
            frames[-1]["cell"] = [float(line[6 + 9 * i:15 + 9 * i]) for i in range(3)]
            frames[-1]["angles"] = [float(line[33 + 7 * i:40 + 7 * i]) for i in range(3)]
            frames[-1]["space_group"] = line[55:66].strip()
        elif line.startswith("ATOM  "):
            frames[-1]["serial"].append(int(line[6:11]))
            frames[-1]["name"].append(line[12:16].strip())
            frames[-1]["xyz"].append([float(line[30:38]), float(line[38:46]), float(line[46:54])])
        elif line.startswith("ENDMDL"):
            frames[-1]["xyz"] = np.array(frames[-1]["xyz"])
    return frames


def read_dcd(path):
    """CHARMM/NAMD DCD, little-endian: Fortran records (int32 length, payload, int32 length). Header
    record: 'CORD' + 20 int32 (NSET, ISTART, NSAVC, NSTEP, ..., DELTA as float32 at word 9, unit-cell
    flag at word 10, CHARMM version at word 19); title record; atom-count record; then per frame an
    optional unit-cell record of 6 float64 (A, gamma, B, beta, alpha, C) and x, y, z records of float32."""
    data = path.read_bytes()
    offset = 0

    def record():
        nonlocal offset
        (length,) = struct.unpack_from("<i", data, offset)
        payload = data[offset + 4:offset + 4 + length]
        (end,) = struct.unpack_from("<i", data, offset + 4 + length)
        assert end == length, f"record at byte {offset}: markers {length} and {end} differ"
        offset += 8 + length
        return payload

    head = record()
    assert len(head) == 84 and head[:4] == b"CORD"
    control = struct.unpack("<20i", head[4:])
    header = {"nset": control[0], "istart": control[1], "nsavc": control[2], "nstep": control[3],
              "delta": struct.unpack("<f", head[4 + 36:4 + 40])[0], "unit_cell": control[10] == 1,
              "version": control[19]}
    title = record()
    (lines,) = struct.unpack_from("<i", title)
    header["titles"] = [title[4 + 80 * i:4 + 80 * (i + 1)].decode().rstrip() for i in range(lines)]
    (header["natoms"],) = struct.unpack("<i", record())
    n = header["natoms"]
    frames = []
    while offset < len(data):
        cell = struct.unpack("<6d", record()) if header["unit_cell"] else None
        xyz = np.stack([np.frombuffer(record(), dtype="<f4", count=n) for _ in range(3)], axis=1)
        frames.append({"cell": cell, "xyz": xyz})
    return header, frames


# ---- checks -----------------------------------------------------------------------------------

@pytest.fixture
def sim(options):
    with structmd.Simulation(options) as s:
        yield s


def expected_frames(record, pbc):
    steps = written_steps(0, STEPS)
    return steps, [record[s][0 if pbc else 1] for s in steps]


def assert_positions(read, expected, pbc, atol):
    np.testing.assert_allclose(read, expected, rtol=0, atol=atol)
    if pbc:
        assert np.all(read >= -BOX / 2 - atol) and np.all(read <= BOX / 2 + atol)


def test_the_run_crosses_the_boundary(sim):
    record = run_and_record(sim, document({}))
    _, unwrapped = record[STEPS]
    crossed = np.any(np.abs(unwrapped) > BOX / 2, axis=1)
    assert crossed.sum() >= 2, "the test system must cross the boundary for pbc=false to mean anything"


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_xyz(sim, tmp_path, pbc):
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "xyz", pbc=pbc)}))
    frames = read_xyz(tmp_path / "traj.xyz")
    steps, expected = expected_frames(record, pbc)
    assert [f["step"] for f in frames] == steps
    names = [TYPES[t][0] for t in sim.types]
    for frame, positions in zip(frames, expected):
        assert frame["names"] == names
        assert frame["type"] == list(sim.types)
        # Z: the atomic number of a name that is an element symbol, else 0 (ASE's dummy atom).
        assert frame["Z"] == [ELEMENTS.get(name, 0) for name in names]
        assert f'Lattice="{BOX[0]:g} 0 0 0 {BOX[1]:g} 0 0 0 {BOX[2]:g}"' in frame["comment"]
        assert "Properties=species:S:1:pos:R:3:Z:I:1:type:I:1" in frame["comment"]
        assert_positions(frame["xyz"], positions, pbc, atol=1e-6)


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_sp(sim, tmp_path, pbc):
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "sp", pbc=pbc)}))
    frames = read_sp(tmp_path / "traj.sp")
    steps, expected = expected_frames(record, pbc)
    assert len(frames) == len(steps)
    types = np.asarray(sim.types)
    for frame, positions in zip(frames, expected):
        np.testing.assert_array_equal(frame["half_box"], BOX / 2)
        np.testing.assert_array_equal(frame["type"], types)
        np.testing.assert_array_equal(frame["radius"], [TYPES[t][2] for t in types])
        assert_positions(frame["xyz"], positions, pbc, atol=1e-6)


def rows_of(path, skip_header=lambda line: False):
    """The numeric rows of a headerless text format, frames one after the other."""
    return np.array([[float(v) for v in line.split()] for line in path.read_text().splitlines()
                     if line.strip() and not skip_header(line)])


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_uammd_structured_velocity_and_force_formats(sim, tmp_path, pbc):
    """coord ("id x y z vx vy vz"), vel ("vx vy vz |v|"), itpv (N, a blank line, "id type x y z vx vy vz")
    and spf (sp with "fx fy fz" after the type), as UAMMD-structured's Output.cu writes them."""
    writers = {name: writer(tmp_path / "traj", name, pbc=pbc) for name in ("coord", "vel", "itpv", "spf")}
    record = run_and_record(sim, document(writers), motion=True)
    steps = written_steps(0, STEPS)
    n = len(sim.types)
    ids = np.arange(n)
    types = np.asarray(sim.types)
    position = lambda s: record[s][0 if pbc else 1]

    coord = rows_of(tmp_path / "traj.coord").reshape(len(steps), n, 7)
    velocity = rows_of(tmp_path / "traj.vel").reshape(len(steps), n, 4)
    itpv_lines = (tmp_path / "traj.itpv").read_text().splitlines()
    assert itpv_lines[:2] == [str(n), ""] and len(itpv_lines) == len(steps) * (n + 2)
    itpv = np.array([[float(v) for v in line.split()] for k, line in enumerate(itpv_lines) if k % (n + 2) >= 2])
    itpv = itpv.reshape(len(steps), n, 8)
    spf = read_sp(tmp_path / "traj.spf")
    assert len(spf) == len(steps)
    for k, step in enumerate(steps):
        _, _, v, forces = record[step]
        np.testing.assert_array_equal(coord[k][:, 0], ids)
        assert_positions(coord[k][:, 1:4], position(step), pbc, atol=1e-6)
        np.testing.assert_allclose(coord[k][:, 4:7], v, rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(velocity[k][:, :3], v, rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(velocity[k][:, 3], np.linalg.norm(v, axis=1), rtol=1e-7, atol=1e-7)
        np.testing.assert_array_equal(itpv[k][:, 0], ids)
        np.testing.assert_array_equal(itpv[k][:, 1], types)
        assert_positions(itpv[k][:, 2:5], position(step), pbc, atol=1e-6)
        np.testing.assert_allclose(itpv[k][:, 5:8], v, rtol=1e-7, atol=1e-7)
        half_box, rows = spf[k]["half_box"], spf[k]["rows"]
        np.testing.assert_array_equal(half_box, BOX / 2)
        assert_positions(rows[:, :3], position(step), pbc, atol=1e-6)
        np.testing.assert_array_equal(rows[:, 3], [TYPES[t][2] for t in types])
        np.testing.assert_array_equal(rows[:, 4], types)
        np.testing.assert_allclose(rows[:, 5:8], forces, rtol=1e-7, atol=1e-6)
    assert np.any(np.abs(spf[-1]["rows"][:, 5:8]) > 1e-3), "the LJ particles must feel forces for spf to mean anything"


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_lammpstrj(sim, tmp_path, pbc):
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "lammpstrj", pbc=pbc)}))
    frames = read_lammpstrj(tmp_path / "traj.lammpstrj")
    steps, expected = expected_frames(record, pbc)
    assert [f["step"] for f in frames] == steps
    for frame, positions in zip(frames, expected):
        assert frame["columns"] == (["id", "type", "x", "y", "z"] if pbc else ["id", "type", "xu", "yu", "zu"])
        np.testing.assert_array_equal(frame["bounds"], np.stack([-BOX / 2, BOX / 2], axis=1))
        np.testing.assert_array_equal(frame["id"], np.arange(1, 21))
        np.testing.assert_array_equal(frame["type"], np.asarray(sim.types) + 1)
        assert_positions(frame["xyz"], positions, pbc, atol=1e-6)


def molecules_document(writers):
    """document() with residues and chains in the structure, two bond terms naming the pair 0-1
    both ways, and an angle (three-particle terms give no CONECT record)."""
    doc = document(writers)
    n = len(doc["state"]["data"])
    residues = [9990 + 3 * i for i in range(n)]  # past 9999: PDB's four columns wrap
    chains = [i // 7 for i in range(n)]
    chains[-1] = 52  # the 53rd letter: A-Z, a-z, then digits
    doc["topology"]["structure"] = {"labels": ["id", "type", "resId", "chainId"],
                                    "data": [[i, row[1], residues[i], chains[i]]
                                             for i, row in enumerate(doc["topology"]["structure"]["data"])]}
    positions = np.array([row[1] for row in doc["state"]["data"]])

    def bonded(pairs):
        return [[i, j, float(np.linalg.norm(minimum_image(positions[i] - positions[j])))] for i, j in pairs]

    doc["topology"]["forceField"]["chain"] = {"type": ["Bond2", "Harmonic"],
                                              "labels": ["id_i", "id_j", "K", "r0"],
                                              "data": [row[:2] + [5.0, row[2]] for row in bonded([(0, 1), (1, 2), (1, 5)])]}
    doc["topology"]["forceField"]["again"] = {"type": ["Bond2", "Harmonic"],
                                              "labels": ["id_i", "id_j", "K", "r0"],
                                              "data": [row[:2] + [1.0, row[2]] for row in bonded([(1, 0), (12, 19)])]}
    doc["topology"]["forceField"]["angle"] = {"type": ["Bond3", "HarmonicAngularCommon_K_theta0"],
                                              "parameters": {"K": 1.0, "theta0": 2.0},
                                              "labels": ["id_i", "id_j", "id_k"], "data": [[3, 4, 8]]}
    return doc, residues, chains


def test_pdb_residues_chains_and_conect_records(sim, tmp_path):
    doc, residues, chains = molecules_document({"traj": writer(tmp_path / "traj", "pdb")})
    sim.load(doc)
    sim.step(STEPS)
    lines = (tmp_path / "traj.pdb").read_text().splitlines()
    atoms = [line for line in lines if line.startswith("ATOM  ")]
    n = len(residues)
    letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
    assert [line[21] for line in atoms[:n]] == [letters[c % len(letters)] for c in chains]
    assert [int(line[22:26]) for line in atoms[:n]] == [r % 10000 for r in residues]
    assert [line[17:20] for line in atoms[:n]] == ["UNK"] * n
    types = [row[1] for row in doc["topology"]["structure"]["data"]]
    assert [line[76:78].strip() for line in atoms[:n]] == [t if t in ELEMENTS else "X" for t in types]
    # CONECT in the first model only, each bonded pair once per side, serials id + 1.
    conect = [line for line in lines if line.startswith("CONECT")]
    assert conect == ["CONECT    1    2", "CONECT    2    1    3    6", "CONECT    3    2",
                      "CONECT    6    2", "CONECT   13   20", "CONECT   20   13"]
    first_end = lines.index("ENDMDL")
    assert all(lines.index(line) < first_end for line in conect)


def test_pdb_with_bonds_reads_in_ase(sim, tmp_path):
    ase_io = pytest.importorskip("ase.io")
    doc, _, _ = molecules_document({"traj": writer(tmp_path / "traj", "pdb")})
    record = run_and_record(sim, doc)
    steps, expected = expected_frames(record, True)
    frames = ase_io.read(tmp_path / "traj.pdb", format="proteindatabank", index=":")
    assert len(frames) == len(steps)
    numbers = [ELEMENTS.get(row[1], 0) for row in doc["topology"]["structure"]["data"]]
    for atoms, positions in zip(frames, expected):
        np.testing.assert_allclose(atoms.positions, positions, atol=5.1e-4)
        assert atoms.numbers.tolist() == numbers


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_pdb(sim, tmp_path, pbc):
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "pdb", pbc=pbc)}))
    frames = read_pdb(tmp_path / "traj.pdb")
    steps, expected = expected_frames(record, pbc)
    assert [f["model"] for f in frames] == list(range(1, len(steps) + 1))
    names = [TYPES[t][0][:4] for t in sim.types]
    for frame, positions in zip(frames, expected):
        assert frame["cell"] == BOX.tolist()
        assert frame["angles"] == [90.0, 90.0, 90.0]
        assert frame["space_group"] == "P 1"
        assert frame["serial"] == list(range(1, 21))
        assert frame["name"] == names
        assert_positions(frame["xyz"], positions, pbc, atol=5.1e-4)


@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_dcd(sim, tmp_path, pbc):
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "dcd", pbc=pbc)}))
    header, frames = read_dcd(tmp_path / "traj.dcd")
    steps, expected = expected_frames(record, pbc)
    assert header["nset"] == len(frames) == len(steps)
    assert header["istart"] == steps[0]
    assert header["nsavc"] == INTERVAL
    assert header["nstep"] == steps[-1] - steps[0]
    assert header["delta"] == np.float32(TIME_STEP)
    assert header["natoms"] == 20
    assert header["unit_cell"] and header["version"] == 24
    for frame, positions in zip(frames, expected):
        a, gamma, b, beta, alpha, c = frame["cell"]
        assert (a, b, c) == tuple(BOX) and (alpha, beta, gamma) == (90.0, 90.0, 90.0)
        assert frame["xyz"].dtype == np.float32
        np.testing.assert_allclose(frame["xyz"], positions, rtol=2.0 ** -23, atol=1e-7)
        if pbc:
            assert_positions(frame["xyz"], positions, pbc, atol=1e-6)


def read_psf(path):
    """An X-PLOR/NAMD PSF as its format is published: a "PSF" flags line, a title section, then
    sections "<count> !<NAME>": atoms one a line (serial segment residue resname name type charge
    mass ...), then bonds, angles and dihedrals as serials, 2, 3 and 4 to a tuple."""
    lines = iter(path.read_text().splitlines())
    assert next(lines).split()[0] == "PSF"
    sections = {}
    for line in lines:
        words = line.split()
        if len(words) < 2 or not words[1].startswith("!"):
            continue
        count, name = int(words[0]), words[1].strip("!:")
        if name == "NTITLE":
            sections[name] = [next(lines) for _ in range(count)]
        elif name == "NATOM":
            sections[name] = [next(lines).split() for _ in range(count)]
        else:
            width = {"NBOND": 2, "NTHETA": 3, "NPHI": 4, "NIMPHI": 4}.get(name, 1)
            numbers = []
            while len(numbers) < width * count:
                numbers += [int(v) for v in next(lines).split()]
            sections[name] = [tuple(numbers[k:k + width]) for k in range(0, len(numbers), width)]
    return sections


CHARGED_TYPES = [["A", 1.0, 0.5, -1.0], ["Polymer", 2.0, 0.7, 0.25], ["Na", 1.5, 0.6, 1.0]]


def charged_molecules_document(writers):
    doc, residues, chains = molecules_document(writers)
    doc["global"]["types"]["data"] = CHARGED_TYPES
    return doc, residues, chains


@pytest.mark.parametrize("group", [None, "heavy"], ids=["all", "group"])
def test_dcd_has_a_psf_topology_beside_it(sim, tmp_path, group):
    """The PSF beside the DCD lists the particles written, in the DCD's order, with their type names,
    masses, charges, residues and chains, and the bonds, angles and dihedrals among them by their
    position in the DCD (1-based)."""
    parameters = {"group": group} if group else {}
    doc, residues, chains = charged_molecules_document({"traj": writer(tmp_path / "traj", "dcd", **parameters)})
    force_field = doc["topology"]["forceField"]
    force_field["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                             "data": [["heavy", "Ids", [0, 1, 2, 5, 7, 12, 19]]]}
    force_field["torsion"] = {"type": ["Bond4", "Dihedral"], "labels": ["id_i", "id_j", "id_k", "id_l", "K", "n", "phi0"],
                              "data": [[0, 1, 2, 5, 1.0, 1, 0.0], [3, 4, 8, 9, 1.0, 1, 0.0]]}
    sim.load(doc)
    sim.step(STEPS)
    psf = read_psf(tmp_path / "traj.psf")
    header, _ = read_dcd(tmp_path / "traj.dcd")
    ids = [0, 1, 2, 5, 7, 12, 19] if group else list(range(20))
    serial = {i: k + 1 for k, i in enumerate(ids)}
    assert len(psf["NATOM"]) == header["natoms"] == len(ids)
    types = {row[0]: row for row in CHARGED_TYPES}
    for k, (i, atom) in enumerate(zip(ids, psf["NATOM"])):
        name = doc["topology"]["structure"]["data"][i][1]
        assert int(atom[0]) == k + 1
        assert atom[1] == f"S{chains[i]}" and int(atom[2]) == residues[i]
        assert atom[4] == atom[5] == name
        assert float(atom[6]) == pytest.approx(types[name][3]) and float(atom[7]) == pytest.approx(types[name][1])
    # Bonds: (0,1), (1,2), (1,5) and (1,0) again, (12,19); the angle 3-4-8 and dihedral 3-4-8-9 only
    # with all their particles written.
    bonds = [(0, 1), (1, 2), (1, 5), (12, 19)]
    assert sorted(tuple(sorted(b)) for b in psf["NBOND"]) == [(serial[i], serial[j]) for i, j in bonds]
    assert psf["NTHETA"] == ([] if group else [(4, 5, 9)])
    assert psf["NPHI"] == ([(1, 2, 3, 4)] if group else [(1, 2, 3, 6), (4, 5, 9, 10)])


def test_mdanalysis_reads_the_psf_and_dcd(sim, tmp_path):
    """MDAnalysis loads the pair as a Universe: names, masses, charges and bonds from the PSF, each
    frame's positions and box from the DCD."""
    mda = pytest.importorskip("MDAnalysis")
    doc, _, _ = charged_molecules_document({"traj": writer(tmp_path / "traj", "dcd")})
    record = run_and_record(sim, doc)
    steps, expected = expected_frames(record, True)
    universe = mda.Universe(str(tmp_path / "traj.psf"), str(tmp_path / "traj.dcd"))
    names = [row[1] for row in doc["topology"]["structure"]["data"]]
    types = {row[0]: row for row in CHARGED_TYPES}
    assert list(universe.atoms.names) == names
    np.testing.assert_allclose(universe.atoms.masses, [types[n][1] for n in names])
    np.testing.assert_allclose(universe.atoms.charges, [types[n][3] for n in names])
    assert sorted(tuple(sorted(b)) for b in universe.bonds.indices.tolist()) == [(0, 1), (1, 2), (1, 5), (12, 19)]
    assert len(universe.trajectory) == len(steps)
    for timestep, positions in zip(universe.trajectory, expected):
        np.testing.assert_allclose(timestep.positions, positions, rtol=0, atol=1e-5)
        np.testing.assert_allclose(timestep.dimensions, BOX.tolist() + [90.0, 90.0, 90.0], rtol=1e-6)


@pytest.mark.parametrize("other_time_step", ["global", "unscheduled integrator first"])
def test_the_time_step_written_is_the_one_the_integrator_steps_with(sim, tmp_path, other_time_step):
    """DCD's DELTA and xyz's time follow the integrator's own timeStep, not global.fundamental's nor
    that of an integrator scheduled first for no steps."""
    doc = document({"dcd": writer(tmp_path / "traj", "dcd"), "xyz": writer(tmp_path / "traj", "xyz")})
    if other_time_step == "global":
        doc["global"]["fundamental"]["parameters"]["timeStep"] = 3 * TIME_STEP
    else:
        doc["integrator"]["idle"] = {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": 3 * TIME_STEP}}
        doc["integrator"]["schedule"]["data"] = [[1, "idle", 0], [2, "vv", STEPS]]
    run_and_record(sim, doc)
    assert sim.time == pytest.approx(STEPS * TIME_STEP, rel=1e-12)
    header, _ = read_dcd(tmp_path / "traj.dcd")
    assert header["delta"] == np.float32(TIME_STEP)
    for frame in read_xyz(tmp_path / "traj.xyz"):
        time = float(frame["comment"].split("time=")[1].split()[0])
        assert time == pytest.approx(frame["step"] * TIME_STEP, rel=1e-7)


def test_dcd_after_a_minimisation_has_the_time_step_of_the_dynamics(sim, tmp_path):
    """A schedule that minimises first: DELTA is the dynamics' time step, not the minimiser's none
    (0 put every frame at time 0 in MDAnalysis)."""
    doc = document({"dcd": writer(tmp_path / "traj", "dcd")})
    doc["integrator"]["minimise"] = {"type": ["SteepestDescent", "SteepestDescent"],
                                     "parameters": {"h": 0.001, "maxObjectiveForce": 10.0}}
    doc["integrator"]["schedule"]["data"] = [[1, "minimise", 3], [2, "vv", STEPS]]
    sim.load(doc)
    sim.run()
    header, _ = read_dcd(tmp_path / "traj.dcd")
    assert header["delta"] == np.float32(TIME_STEP)


@pytest.mark.parametrize("output_format", FORMATS)
def test_append_keeps_the_earlier_frames(options, tmp_path, output_format):
    path = tmp_path / f"traj.{output_format}"
    with structmd.Simulation(options) as first:
        run_and_record(first, document({"traj": writer(tmp_path / "traj", output_format)}))
    earlier = path.read_bytes()
    with structmd.Simulation(options) as second:
        later = run_and_record(second, document({"traj": writer(tmp_path / "traj", output_format, append=True)},
                                                current_step=100))
    grown = path.read_bytes()
    first_steps, later_steps = written_steps(0, STEPS), written_steps(100, 100 + STEPS)
    if output_format == "dcd":
        header, frames = read_dcd(path)
        assert header["nset"] == len(frames) == len(first_steps) + len(later_steps)
        assert header["istart"] == 0, "appending keeps the first file's ISTART"
        assert header["nstep"] == 100 + STEPS
        assert grown[276:len(earlier)] == earlier[276:], "the earlier frames must be kept as they were"
        for frame, step in zip(frames[len(first_steps):], later_steps):
            np.testing.assert_allclose(frame["xyz"], later[step][0], rtol=2.0 ** -23, atol=1e-7)
    else:
        assert grown.startswith(earlier), "the earlier frames must be kept as they were"
        reader = {"xyz": read_xyz, "sp": read_sp, "lammpstrj": read_lammpstrj, "pdb": read_pdb}[output_format]
        frames = reader(path)
        assert len(frames) == len(first_steps) + len(later_steps)
        if output_format == "pdb":
            assert [f["model"] for f in frames] == list(range(1, len(frames) + 1))
        if output_format in ("xyz", "lammpstrj"):
            assert [f["step"] for f in frames] == first_steps + later_steps

    with structmd.Simulation(options) as third:
        run_and_record(third, document({"traj": writer(tmp_path / "traj", output_format)}))
    assert path.read_bytes() == earlier, "append=false starts the file again"


def test_dcd_append_refuses_a_file_of_another_system(options, tmp_path):
    with structmd.Simulation(options) as first:
        run_and_record(first, document({"traj": writer(tmp_path / "traj", "dcd")}))
    doc = document({"traj": writer(tmp_path / "traj", "dcd", append=True)})
    doc["state"]["data"] = doc["state"]["data"][:19]
    doc["topology"]["structure"]["data"] = doc["topology"]["structure"]["data"][:19]
    with structmd.Simulation(options) as second:
        second.load(doc)
        with pytest.raises(structmd.StructmdIOError, match=r"traj\.dcd.*20 particles, the simulation 19"):
            second.step(1)


def test_an_unknown_format_names_the_parameter_and_the_known_ones(sim, tmp_path):
    with pytest.raises(structmd.InputError,
                       match=r"simulationStep\.traj\.parameters\.outputFormat.*'gro'.*xyz, sp, spf, lammpstrj, dcd, pdb, coord, vel, itpv"):
        sim.load(document({"traj": writer(tmp_path / "traj", "gro")}))


def test_a_path_in_a_missing_folder_is_refused_at_load(sim, tmp_path):
    target = tmp_path / "no_such_folder" / "traj"
    with pytest.raises(structmd.StructmdIOError) as error:
        sim.load(document({"traj": writer(target, "xyz")}))
    assert str(error.value).startswith("simulationStep.traj.parameters.outputFilePath: ")
    assert f"'{tmp_path / 'no_such_folder'}' does not exist" in str(error.value)


def test_an_unwritable_path_is_an_io_error_at_the_first_firing(sim, tmp_path):
    folder = tmp_path / "folder"
    folder.mkdir()
    target = folder / "traj"
    sim.load(document({"traj": writer(target, "xyz")}))  # nothing is opened at load
    folder.rmdir()
    with pytest.raises(structmd.StructmdIOError) as error:
        sim.step(1)
    assert str(target) + ".xyz" in str(error.value)
    assert "No such file or directory" in str(error.value)


@pytest.mark.parametrize("output_format", ["lammpstrj", "pdb", "dcd"])
def test_a_group_writes_only_its_particles_with_their_ids(sim, tmp_path, output_format):
    doc = document({"traj": writer(tmp_path / "traj", output_format, group="heavy")})
    doc["topology"]["forceField"]["groups"] = {"type": ["Groups", "GroupsList"], "labels": ["name", "type", "selection"],
                                               "data": [["heavy", "Types", ["Polymer"]]]}
    record = run_and_record(sim, doc)
    members = np.flatnonzero(np.asarray(sim.types) == 1)
    assert 0 < len(members) < 20
    path = tmp_path / f"traj.{output_format}"
    if output_format == "dcd":
        header, frames = read_dcd(path)
        assert header["natoms"] == len(members)
    else:
        frames = (read_lammpstrj if output_format == "lammpstrj" else read_pdb)(path)
        for frame in frames:
            ids = frame["id"] if output_format == "lammpstrj" else np.array(frame["serial"])
            np.testing.assert_array_equal(ids, members + 1)
    assert len(frames) == len(written_steps(0, STEPS))
    for frame, step in zip(frames, written_steps(0, STEPS)):
        np.testing.assert_allclose(frame["xyz"], record[step][0][members], rtol=0, atol=5.1e-4)


def test_a_host_stepping_in_a_loop_finds_every_due_frame_on_disk_when_each_call_returns(options, tmp_path):
    """A schedule far longer than the loop: after each structmd_step the frames due up to the step
    reached are in the file, the last one included, with the state the steps reached, not one the host
    sets afterwards; destroying the handle there loses none (LAMMPS's run N, OpenMM's step(n))."""
    path = tmp_path / "traj.lammpstrj"
    with structmd.Simulation(options) as sim:
        sim.load(document({"traj": writer(tmp_path / "traj", "lammpstrj")}, steps=1000))
        reached = {0: np.asarray(sim.positions)}
        for call in range(4):
            sim.step(INTERVAL if call != 2 else INTERVAL + 1)
            reached[sim.step_number] = np.asarray(sim.positions)
            frames = read_lammpstrj(path)
            assert [f["step"] for f in frames] == list(range(0, sim.step_number + 1, INTERVAL))
            # The host moves the particles between calls: the frame already written keeps the
            # state the steps reached.
            sim.positions = np.asarray(sim.positions) * 0.999
    frames = read_lammpstrj(path)
    assert [f["step"] for f in frames] == [0, 3, 6, 9, 12]
    for frame in frames[:3]:  # the frames at the steps where calls ended: 0, 3 and 6
        np.testing.assert_allclose(frame["xyz"], reached[frame["step"]], rtol=0, atol=1e-6)


def test_an_unknown_group_names_the_parameter(sim, tmp_path):
    with pytest.raises(structmd.InputError, match=r"simulationStep\.traj\.parameters\.group.*'nowhere'"):
        sim.load(document({"traj": writer(tmp_path / "traj", "xyz", group="nowhere")}))


LAMMPS = shutil.which("lmp")


@pytest.mark.skipif(LAMMPS is None, reason="LAMMPS (lmp) is not installed")
@pytest.mark.parametrize("pbc", [True, False], ids=["wrapped", "unwrapped"])
def test_lammps_reads_the_lammpstrj(sim, tmp_path, pbc):
    """LAMMPS's own read_dump takes the file (x y z or xu yu zu); it writes back what it read."""
    record = run_and_record(sim, document({"traj": writer(tmp_path / "traj", "lammpstrj", pbc=pbc)}))
    final = written_steps(0, STEPS)[-1]
    script = "\n".join([
        "units lj", "atom_style atomic", "boundary p p p",
        f"region box block {-BOX[0] / 2} {BOX[0] / 2} {-BOX[1] / 2} {BOX[1] / 2} {-BOX[2] / 2} {BOX[2] / 2}",
        "create_box 2 box", "mass * 1.0",
        f"read_dump traj.lammpstrj {final} x y z box yes add keep",
        "write_dump all custom back.txt id type xu yu zu modify sort id format float %.10g",
    ])
    (tmp_path / "in.lmp").write_text(script + "\n")
    subprocess.run([LAMMPS, "-in", "in.lmp", "-log", "none", "-screen", "none"], cwd=tmp_path, check=True,
                   timeout=60)
    rows = [line.split() for line in (tmp_path / "back.txt").read_text().splitlines()[9:]]
    back = np.array([[float(v) for v in row[2:5]] for row in rows])
    np.testing.assert_array_equal([int(row[1]) for row in rows], np.asarray(sim.types) + 1)
    np.testing.assert_allclose(back, record[final][0 if pbc else 1], rtol=0, atol=1e-6)
