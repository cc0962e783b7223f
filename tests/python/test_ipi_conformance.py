"""One i-PI conformance test for both clients, structmd.ipi.run (in a thread) and the launcher's
`structmd client --ipi` (a subprocess): a scripted fake server on a UNIX socket or on loopback TCP sends
each client the same messages and holds both to the same answers. test_ipi.py checks the clients
against a real server (ASE's); this file checks what a well-behaved server never shows them: the exact
bytes of every reply, the unit conversions against ase.units rather than the clients' own constants,
and malformed messages, which each client must refuse with the same status, promptly, hanging up
rather than waiting for more."""

import itertools
import json
import os
import re
import socket
import struct
import subprocess
import threading
from typing import NamedTuple, Optional

import ase.units
import numpy as np
import pytest

import structmd
import structmd.ipi
from systems import SIGMA, EPSILON, lj_input, rattled_argon

LAUNCHER = os.environ.get("STRUCTMD_LAUNCHER")
TIMEOUT = 30.0  # s; the longest any side waits for the other, so that a client that hangs fails the test
READ_TIMEOUT = 2.0  # s; the clients' own limit on a silent server, well within TIMEOUT
HEADER_SIZE = 12
# The input is in reduced Lennard-Jones units, so that the unit conversions are not the identity.
LENGTH_UNIT, ENERGY_UNIT = SIGMA, EPSILON  # one input length in Å, one input energy in eV
_names = itertools.count()


class Outcome(NamedTuple):
    status: str  # a STRUCTMD_ status name; "hung" for a client still running after TIMEOUT
    message: str
    evaluations: Optional[int]  # configurations evaluated, when the client ended normally


class PythonClient:
    """structmd.ipi.run in a thread. Both client types are built alike: (document, options, tmp_path)."""

    def __init__(self, document, options, tmp_path):
        self.document, self.options, self.thread, self.outcome = document, options, None, None

    def start(self, address):
        def serve():
            try:
                evaluations = structmd.ipi.run(address, self.document, options=self.options, length_unit=LENGTH_UNIT,
                                               energy_unit=ENERGY_UNIT, connect_timeout=TIMEOUT,
                                               read_timeout=READ_TIMEOUT)
                self.outcome = Outcome("STRUCTMD_OK", "", evaluations)
            except structmd.StructmdError as error:
                self.outcome = Outcome(error.status_name, str(error), None)
            except ConnectionError as error:  # docs/python.md: the launcher's STRUCTMD_ERR_IO
                self.outcome = Outcome("STRUCTMD_ERR_IO", str(error), None)
            except BaseException as error:  # anything else is a failure of the test, reported by finish
                self.outcome = Outcome("unexpected", repr(error), None)

        self.thread = threading.Thread(target=serve, daemon=True)
        self.thread.start()

    def finish(self):
        self.thread.join(timeout=TIMEOUT)
        return Outcome("hung", "", None) if self.thread.is_alive() else self.outcome


class LauncherClient:
    """`structmd client --ipi` in a subprocess, on the document written under tmp_path."""

    def __init__(self, document, options, tmp_path):
        self.input_path, self.options, self.process = tmp_path / "input.json", options, None
        self.input_path.write_text(json.dumps(document))

    def start(self, address):
        self.process = subprocess.Popen(
            [LAUNCHER, "client", "--ipi", address, str(self.input_path), "--backend", self.options["backend"],
             "--precision", self.options["precision"], "--length-unit", repr(LENGTH_UNIT), "--energy-unit",
             repr(ENERGY_UNIT), "--connect-timeout", repr(TIMEOUT), "--read-timeout", repr(READ_TIMEOUT)],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def finish(self):
        try:
            output, _ = self.process.communicate(timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            self.process.kill()
            return Outcome("hung", self.process.communicate()[0], None)
        status = {value: name for name, value in structmd.STATUS.items()}.get(self.process.returncode,
                                                                              f"exit {self.process.returncode}")
        done = re.search(r"done after (\d+) configurations", output)
        return Outcome(status, output, int(done.group(1)) if done else None)


class FakeServer:
    """The server's side of the protocol, one message part at a time, so that a test can break any."""

    def __init__(self, kind):
        if kind == "unix":
            name = f"structmd_conformance_{os.getpid()}_{next(_names)}"
            self.path = "/tmp/ipi_" + name  # where i-PI's clients look for unix:NAME
            self.listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            self.listener.bind(self.path)
            self.address = f"unix:{name}"
        else:
            self.path = None
            self.listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            self.listener.bind(("127.0.0.1", 0))
            self.address = f"127.0.0.1:{self.listener.getsockname()[1]}"
        self.listener.listen(1)
        self.listener.settimeout(TIMEOUT)
        self.connection = None

    def accept(self):
        self.connection, _ = self.listener.accept()
        self.connection.settimeout(TIMEOUT)

    def close(self):
        if self.connection is not None:
            self.connection.close()
        self.listener.close()
        if self.path is not None:
            os.unlink(self.path)

    def send(self, *parts):
        self.connection.sendall(b"".join(parts))

    def send_header(self, text):
        self.send(text.encode("ascii").ljust(HEADER_SIZE))

    def receive(self, size):
        data = b""
        while len(data) < size:
            chunk = self.connection.recv(size - len(data))
            assert chunk, f"the client hung up after {len(data)} of {size} bytes"
            data += chunk
        return data

    def status(self):
        self.send_header("STATUS")
        return self.receive(HEADER_SIZE)

    def init(self, length=5):
        self.send_header("INIT")
        self.send(struct.pack("i", 0), struct.pack("i", length), b"bead0"[:max(length, 0)])

    def posdata(self, cell_rows, positions, count=None):
        """cell_rows: lattice vectors as rows, in bohr; sent as columns, as i-PI does, with the inverse."""
        cell = np.asarray(cell_rows, dtype=np.float64)
        self.send_header("POSDATA")
        self.send(np.ascontiguousarray(cell.T).tobytes(), np.ascontiguousarray(np.linalg.inv(cell).T).tobytes(),
                  struct.pack("i", len(positions) if count is None else count),
                  np.ascontiguousarray(positions, dtype=np.float64).tobytes())

    def getforce(self):
        """energy, forces (n, 3), virial (3, 3, as sent: transposed) and the extra string, in atomic units."""
        self.send_header("GETFORCE")
        assert self.receive(HEADER_SIZE) == b"FORCEREADY  "
        energy, = struct.unpack("d", self.receive(8))
        count, = struct.unpack("i", self.receive(4))
        forces = np.frombuffer(self.receive(24 * count), dtype=np.float64).reshape(count, 3)
        virial = np.frombuffer(self.receive(72), dtype=np.float64).reshape(3, 3)
        extra_length, = struct.unpack("i", self.receive(4))
        return energy, forces, virial, self.receive(extra_length)

    def client_hung_up(self):
        """Whether the client closes the connection (rather than wait for more) within TIMEOUT. A client
        that closes with bytes of ours unread resets the connection instead: that is a hang-up too."""
        try:
            return self.connection.recv(1) == b""
        except ConnectionResetError:
            return True
        except socket.timeout:
            return False


@pytest.fixture(params=["python", "launcher"])
def client_type(request):
    if request.param == "launcher" and LAUNCHER is None:
        pytest.skip("STRUCTMD_LAUNCHER not set (ctest sets it)")
    return PythonClient if request.param == "python" else LauncherClient


def configurations():
    """Two configurations of the same 256 argon atoms (Å): rattled, then rattled again in a cell
    stretched by different factors along x, y and z, so that the axes cannot be mixed up unseen."""
    first = rattled_argon(seed=21)
    second = first.copy()
    second.set_cell(np.diag(np.diag(first.cell) * [1.01, 1.03, 1.05]), scale_atoms=True)
    second.rattle(stdev=0.05, seed=22)
    return [first, second]


def document_of(atoms):
    return lj_input(atoms, sigma=1.0, epsilon=1.0, length_unit=LENGTH_UNIT)


def expected_reply(document, atoms, options):
    """What the client must send for atoms, in atomic units: structmd's own results in input units,
    converted with ase.units rather than the clients' constants."""
    with structmd.Simulation(options) as sim:
        sim.load(document)
        sim.box = np.diag(atoms.cell) / LENGTH_UNIT
        sim.positions = atoms.positions / LENGTH_UNIT
        sim.compute(forces=True, energy=True, virial=True)
        hartree = ase.units.Hartree / ENERGY_UNIT
        bohr = ase.units.Bohr / LENGTH_UNIT
        return sim.energy("potential") / hartree, sim.forces * bohr / hartree, sim.virial.T / hartree


def in_bohr(atoms):
    return np.asarray(atoms.cell) / ase.units.Bohr, atoms.positions / ase.units.Bohr


def run_session(client_type, options, tmp_path, script, kind="unix"):
    """Starts a client against a fake server, runs script(server, atoms) and returns the client's
    Outcome once the server has closed the connection."""
    atoms = configurations()[0]
    client = client_type(document_of(atoms), options, tmp_path)
    server = FakeServer(kind)
    try:
        client.start(server.address)
        server.accept()
        script(server, atoms)
    finally:
        server.close()
    return client.finish()


@pytest.mark.parametrize("kind", ["unix", "tcp"])
def test_a_session_answers_every_message_in_atomic_units(client_type, kind, options, tmp_path):
    states = configurations()
    document = document_of(states[0])

    def script(server, _):
        assert server.status() == b"NEEDINIT    "
        server.init()
        assert server.status() == b"READY       "
        for atoms in states:
            server.posdata(*in_bohr(atoms))
            assert server.status() == b"HAVEDATA    "
            energy, forces, virial, extra = server.getforce()
            assert server.status() == b"READY       "
            expected_energy, expected_forces, expected_virial = expected_reply(document, atoms, options)
            assert np.abs(expected_forces).max() > 1e-4  # a real test: the rattle makes forces
            assert energy == pytest.approx(expected_energy, rel=1e-12)
            assert forces.shape == (len(atoms), 3)
            scale = np.abs(expected_forces).max()
            np.testing.assert_allclose(forces, expected_forces, rtol=0, atol=1e-11 * scale)
            np.testing.assert_allclose(virial, expected_virial, rtol=0, atol=1e-11 * np.abs(expected_virial).max())
            assert extra == b""
        server.send_header("EXIT")
        assert server.client_hung_up()

    outcome = run_session(client_type, options, tmp_path, script, kind)
    assert (outcome.status, outcome.evaluations) == ("STRUCTMD_OK", len(states)), outcome


def test_the_server_closing_between_messages_ends_the_client(client_type, options, tmp_path):
    def script(server, atoms):
        server.init()
        server.posdata(*in_bohr(atoms))
        server.getforce()

    outcome = run_session(client_type, options, tmp_path, script)
    assert (outcome.status, outcome.evaluations) == ("STRUCTMD_OK", 1), outcome


def truncated_header(server, atoms):
    server.send(b"POSDA")


def truncated_cell(server, atoms):
    server.send_header("POSDATA")
    server.send(np.zeros(5).tobytes())


def truncated_positions(server, atoms):
    cell, positions = in_bohr(atoms)
    server.posdata(cell, positions[:-1], count=len(atoms))


def unknown_header(server, atoms):
    server.send_header("HELLO")


def header_padded_on_the_left(server, atoms):
    server.send(b"      STATUS")


def negative_init_length(server, atoms):
    server.init(length=-1)


def absurd_init_length(server, atoms):
    # Only the length: a client that believed it allocated 2 GiB, then waited for them.
    server.send_header("INIT")
    server.send(struct.pack("i", 0), struct.pack("i", 2**31 - 1))


def silent_server(server, atoms):
    server.init()  # then nothing: the client must not wait forever


def negative_cell_edge(server, atoms):
    cell, positions = in_bohr(atoms)
    cell[1, 1] = -cell[1, 1]
    server.posdata(cell, positions)


def getforce_before_posdata(server, atoms):
    server.init()
    server.send_header("GETFORCE")


def one_atom_fewer(server, atoms):
    cell, positions = in_bohr(atoms)
    server.posdata(cell, positions[:-1])


def absurd_atom_count(server, atoms):
    # Only the count: a client that believed it would wait for 50 GB of positions.
    cell, _ = in_bohr(atoms)
    server.posdata(cell, np.zeros((0, 3)), count=2**31 - 1)


def negative_atom_count(server, atoms):
    cell, _ = in_bohr(atoms)
    server.posdata(cell, np.zeros((0, 3)), count=-3)


def tilted_cell(server, atoms):
    cell, positions = in_bohr(atoms)
    cell[1, 0] = 0.5  # the second lattice vector leans along x
    server.posdata(cell, positions)


def cell_with_nan(server, atoms):
    cell, positions = in_bohr(atoms)
    cell[0, 1] = np.nan
    server.posdata(cell, positions)


def flat_cell(server, atoms):
    cell, positions = in_bohr(atoms)
    cell[2, 2] = 0.0
    server.send_header("POSDATA")  # by hand: the inverse of a flat cell does not exist
    server.send(cell.T.tobytes(), np.zeros(9).tobytes(), struct.pack("i", len(atoms)), positions.tobytes())


# Cut off by the server: the client can only notice when the connection closes.
TRUNCATED = [truncated_header, truncated_cell, truncated_positions]


@pytest.mark.parametrize("malformed, status, message", [
    (truncated_header, "STRUCTMD_ERR_IO", "in the middle of a message"),
    (truncated_cell, "STRUCTMD_ERR_IO", "in the middle of a message"),
    (truncated_positions, "STRUCTMD_ERR_IO", "in the middle of a message"),
    (unknown_header, "STRUCTMD_ERR_IO", "unknown i-PI message 'HELLO'"),
    (header_padded_on_the_left, "STRUCTMD_ERR_IO", "unknown i-PI message"),
    (negative_init_length, "STRUCTMD_ERR_IO", "INIT with a negative length"),
    (absurd_init_length, "STRUCTMD_ERR_IO", f"INIT announces a string of {2**31 - 1} bytes, more than the"),
    (silent_server, "STRUCTMD_ERR_IO", "no data from the server for 2"),
    (getforce_before_posdata, "STRUCTMD_ERR_IO", "GETFORCE before any POSDATA"),
    (one_atom_fewer, "STRUCTMD_ERR_ARGUMENT", "the input has 256 particles, but the server sent 255 atoms"),
    (absurd_atom_count, "STRUCTMD_ERR_ARGUMENT", f"but the server sent {2**31 - 1} atoms"),
    (negative_atom_count, "STRUCTMD_ERR_ARGUMENT", "but the server sent -3 atoms"),
    (tilted_cell, "STRUCTMD_ERR_UNSUPPORTED", "tilted"),
    (cell_with_nan, "STRUCTMD_ERR_ARGUMENT", "finite"),
    (flat_cell, "STRUCTMD_ERR_ARGUMENT", "positive"),
    (negative_cell_edge, "STRUCTMD_ERR_ARGUMENT", "positive"),  # the launcher called it tilted
], ids=lambda value: value.__name__ if callable(value) else None)
def test_a_malformed_server_is_refused_at_once(client_type, malformed, status, message, options, tmp_path):
    def script(server, atoms):
        malformed(server, atoms)
        if malformed not in TRUNCATED:
            assert server.client_hung_up(), "the client waits for more instead of refusing the message"

    outcome = run_session(client_type, options, tmp_path, script)
    assert outcome.status == status, outcome
    assert message in outcome.message, outcome
