"""The i-PI clients against ASE's SocketIOCalculator, a real i-PI server: structmd.ipi.run in a thread
and the launcher's `structmd client --ipi` in a subprocess, over TCP and over a UNIX socket. The
energy, forces and stress ASE receives for two configurations (so that POSDATA updates the positions
and the cell) must be structmd's own for the same positions, converted by ASE from atomic units."""

import json
import os
import socket
import subprocess
import threading

import numpy as np
import pytest
from ase.calculators.socketio import SocketIOCalculator
from ase.stress import full_3x3_to_voigt_6_stress

import structmd
import structmd.ipi
from systems import lj_input, rattled_argon

LAUNCHER = os.environ.get("STRUCTMD_LAUNCHER")
SERVER_TIMEOUT = 120.0  # s; a client that dies leaves the server waiting no longer than this


def free_port():
    with socket.socket() as probe:
        probe.bind(("", 0))
        return probe.getsockname()[1]


def server_and_address(kind, tag):
    """An ASE i-PI server listening, and the address a client gives to reach it; names are unique
    per process so that tests may run side by side."""
    if kind == "tcp":
        port = free_port()
        return SocketIOCalculator(port=port, timeout=SERVER_TIMEOUT), f"localhost:{port}"
    name = f"structmd_{tag}_{os.getpid()}"
    return SocketIOCalculator(unixsocket=name, timeout=SERVER_TIMEOUT), f"unix:{name}"


def structmd_reference(document, atoms, options):
    """Energy, forces and stress (ASE units, which the input is in) computed by structmd directly."""
    with structmd.Simulation(options) as sim:
        sim.load(document)
        sim.box = [atoms.cell[k, k] for k in range(3)]
        sim.positions = atoms.positions
        sim.compute(forces=True, energy=True, virial=True)
        stress = full_3x3_to_voigt_6_stress(-sim.virial / atoms.get_volume())
        return sim.energy("potential"), sim.forces, stress


def configurations():
    """Two configurations of the same 256 atoms: rattled, then rattled again in a 2% larger cell."""
    atoms = rattled_argon(seed=11)
    second = atoms.copy()
    second.set_cell(second.cell * 1.02, scale_atoms=True)
    second.rattle(stdev=0.05, seed=12)
    return atoms, [atoms, second]


def assert_server_receives_structmd_results(calc, document, states, options):
    for atoms in states:
        atoms = atoms.copy()
        atoms.calc = calc
        energy, forces, stress = structmd_reference(document, atoms, options)
        assert np.abs(forces).max() > 1e-3  # a real test: the rattle makes forces
        assert atoms.get_potential_energy() == pytest.approx(energy, rel=1e-12, abs=1e-12)
        np.testing.assert_allclose(atoms.get_forces(), forces, rtol=0, atol=1e-11 * np.abs(forces).max())
        np.testing.assert_allclose(atoms.get_stress(), stress, rtol=0, atol=1e-11 * np.abs(stress).max())


@pytest.mark.parametrize("kind", ["tcp", "unix"])
def test_python_client_answers_ase_server(kind, options):
    start, states = configurations()
    document = lj_input(start)
    calc, address = server_and_address(kind, "python")
    outcome = {}

    def client():
        try:
            outcome["evaluations"] = structmd.ipi.run(address, document, options=options)
        except BaseException as error:  # reported by the test thread below
            outcome["error"] = error

    thread = threading.Thread(target=client, daemon=True)
    with calc:
        thread.start()
        assert_server_receives_structmd_results(calc, document, states, options)
    thread.join(timeout=SERVER_TIMEOUT)
    assert not thread.is_alive()
    assert "error" not in outcome, outcome.get("error")
    assert outcome["evaluations"] == len(states)


@pytest.mark.skipif(LAUNCHER is None, reason="STRUCTMD_LAUNCHER not set (ctest sets it)")
@pytest.mark.parametrize("kind", ["tcp", "unix"])
def test_launcher_client_answers_ase_server(kind, options, tmp_path):
    start, states = configurations()
    document = lj_input(start)
    input_path = tmp_path / "argon.json"
    input_path.write_text(json.dumps(document))
    calc, address = server_and_address(kind, "launcher")
    with calc:
        client = subprocess.Popen([LAUNCHER, "client", "--ipi", address, str(input_path),
                                   "--backend", options["backend"], "--precision", options["precision"]],
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            assert_server_receives_structmd_results(calc, document, states, options)
        finally:
            calc.close()
            output, _ = client.communicate(timeout=SERVER_TIMEOUT)
    print(output)
    assert client.returncode == 0, output
    assert f"{len(states)} configurations" in output


def test_a_wrong_number_of_atoms_stops_the_python_client(options):
    start, _ = configurations()
    document = lj_input(start)
    calc, address = server_and_address("unix", "natoms")
    outcome = {}

    def client():
        try:
            structmd.ipi.run(address, document, options=options)
        except BaseException as error:
            outcome["error"] = error

    thread = threading.Thread(target=client, daemon=True)
    fewer = start[:-1]
    with calc:
        thread.start()
        fewer.calc = calc
        with pytest.raises(OSError):
            fewer.get_forces()  # the client hangs up instead of answering
    thread.join(timeout=SERVER_TIMEOUT)
    assert isinstance(outcome.get("error"), structmd.ArgumentError), outcome
    assert f"{len(start)} particles" in str(outcome["error"])


@pytest.mark.parametrize("address", ["localhost", "localhost:", "host:port", ":31415", "unix:", "localhost:70000"])
def test_malformed_addresses_are_refused(address):
    with pytest.raises(structmd.ArgumentError, match="address"):
        structmd.ipi.parse_address(address)


def test_no_server_is_a_connection_error_after_the_timeout():
    with pytest.raises(ConnectionError, match="no i-PI server"):
        structmd.ipi.connect(f"unix:structmd_nobody_{os.getpid()}", timeout=0.3)


@pytest.mark.skipif(LAUNCHER is None, reason="STRUCTMD_LAUNCHER not set (ctest sets it)")
def test_launcher_reports_a_wrong_number_of_atoms_and_exits_with_its_status(options, tmp_path):
    start, _ = configurations()
    input_path = tmp_path / "argon.json"
    input_path.write_text(json.dumps(lj_input(start)))
    calc, address = server_and_address("unix", "launcher_natoms")
    fewer = start[:-1]
    with calc:
        client = subprocess.Popen([LAUNCHER, "client", "--ipi", address, str(input_path), "--backend", options["backend"],
                                   "--quiet"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        fewer.calc = calc
        with pytest.raises(OSError):
            fewer.get_forces()
        output, _ = client.communicate(timeout=SERVER_TIMEOUT)
    assert client.returncode == structmd.STATUS["STRUCTMD_ERR_ARGUMENT"], output
    assert f"the input has {len(start)} particles, but the server sent {len(fewer)} atoms" in output


@pytest.mark.skipif(LAUNCHER is None, reason="STRUCTMD_LAUNCHER not set (ctest sets it)")
@pytest.mark.parametrize("address, status, message", [
    ("localhost:x", "STRUCTMD_ERR_ARGUMENT", "the port must be a number"),
    ("localhost", "STRUCTMD_ERR_ARGUMENT", "expected HOST:PORT or unix:NAME"),
    ("unix:", "STRUCTMD_ERR_ARGUMENT", "needs a NAME"),
    (f"unix:structmd_nobody_{os.getpid()}", "STRUCTMD_ERR_IO", "no i-PI server")])
def test_launcher_reports_a_bad_address_or_an_absent_server(address, status, message, tmp_path):
    input_path = tmp_path / "argon.json"
    input_path.write_text(json.dumps(lj_input(rattled_argon(seed=1))))
    result = subprocess.run([LAUNCHER, "client", "--ipi", address, str(input_path), "--backend", "cpu",
                             "--connect-timeout", "0.3", "--quiet"], capture_output=True, text=True, timeout=60)
    assert result.returncode == structmd.STATUS[status], result.stderr
    assert message in result.stderr
