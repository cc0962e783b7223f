"""The README's claims that drift as the engine grows, held to their sources: its list of integrators
to the integrators docs/input-format.md documents (which tests/python/test_docs_components.py holds
to the engine), and its count of UAMMD-structured inputs to tests/reference/uammd_inputs."""

import json
import re
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
README = " ".join((REPOSITORY / "README.md").read_text(encoding="utf-8").split())
INPUT_FORMAT = (REPOSITORY / "docs" / "input-format.md").read_text(encoding="utf-8")
UAMMD_INPUTS = REPOSITORY / "tests" / "reference" / "uammd_inputs"

# How the README names each documented integrator; a new integrator needs its words here and there.
README_WORDS = {
    ("Verlet", "VelocityVerlet"): "velocity Verlet",
    ("DPD", "Verlet"): "dissipative particle dynamics",
    ("SPH", "Verlet"): "smoothed particle hydrodynamics",
    ("Langevin", "BBK"): "BBK",
    ("Langevin", "GJF"): "Grønbech-Jensen-Farago",
    ("Brownian", "EulerMaruyama"): "Euler-Maruyama",
    ("Brownian", "EulerMaruyamaRigidBody"): "rigid body",
    ("Brownian", "EulerMaruyamaRigidBodyPatchesState"): "rigid patchy bodies",
    ("BDHIOpenBoundary", "Cholesky"): "Cholesky",
    ("BDHIOpenBoundary", "Lanczos"): "Lanczos",
    ("BDHITriplyPeriodic", "ForceCouplingMethod"): "force coupling method",
    ("BDHITriplyPeriodic", "PositivelySplitEwald"): "positively split Ewald",
    ("BDHITriplyPeriodic", "FluctuatingImmersedBoundary"): "fluctuating immersed boundary",
    ("BDHIDoublyPeriodic", "Quasi2D"): "quasi-2D",
    ("BDHIDoublyPeriodic", "DPStokes"): "DPStokes",
    ("FluctuatingHydrodynamics", "IncompressibleInertialCoupling"): "inertial coupling method",
    ("FluctuatingHydrodynamics", "CompressibleInertialCoupling"): "compressible one",
    ("Magnetic", "Fixed"): "Landau-Lifshitz-Gilbert",
    ("Magnetic", "Brownian"): "Brownian rotation",
    ("Magnetic", "ForceCouplingMethod"): "rotation through a fluid",
    ("SteepestDescent", "SteepestDescent"): "steepest descent",
    ("None", "None"): "moves nothing",
    ("Schedule", "Integrator"): "schedule",
}


def documented_integrators():
    section = INPUT_FORMAT[INPUT_FORMAT.index("\n## integrator\n"):INPUT_FORMAT.index("\n## simulationStep\n")]
    return [tuple(pair) for pair in re.findall(r'^### \["([^"]+)","([^"]+)"\]', section, re.MULTILINE)]


def readme_bullet(title):
    start = README.index(f"- {title}:")
    return README[start:README.index(" - ", start + 1)]


def test_every_documented_integrator_is_named_in_the_readme():
    integrators = documented_integrators()
    assert len(integrators) >= 10, integrators
    bullet = readme_bullet("Integrators")
    for integrator in integrators:
        assert integrator in README_WORDS, f"{integrator} is documented but has no words in README_WORDS"
        assert README_WORDS[integrator] in bullet, f"README's integrators do not name {integrator}"


def test_the_readme_counts_the_uammd_inputs_that_load():
    claim = re.search(r"(\d+) of the (\d+) inputs UAMMD-structured's own generators write", README)
    assert claim, "README no longer states how many UAMMD-structured inputs load"
    # generate.py keeps the inputs that load (origins.json maps each to its generator) and lists the
    # others in UNSUPPORTED.md.
    loading = json.loads((UAMMD_INPUTS / "origins.json").read_text(encoding="utf-8"))
    assert sorted(loading) == sorted(path.name for path in UAMMD_INPUTS.glob("*.json") if path.name != "origins.json")
    unsupported = (UAMMD_INPUTS / "UNSUPPORTED.md").read_text(encoding="utf-8")
    table = unsupported[unsupported.index("## Inputs"):].split("\n## ")[0]
    rows = [row for row in table.splitlines() if row.startswith("| ")]
    failing = rows[2:]  # below the header and its "| --- |" line
    assert (int(claim.group(1)), int(claim.group(2))) == (len(loading), len(loading) + len(failing))
