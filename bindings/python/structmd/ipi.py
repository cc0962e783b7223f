"""An i-PI client: structmd answers the force requests of an i-PI server (i-PI itself, or ASE's
SocketIOCalculator) over a TCP or UNIX socket.

    structmd.ipi.run("localhost:31415", "input.json")     # TCP
    structmd.ipi.run("unix:water", "input.json")          # UNIX socket /tmp/ipi_water

The protocol: the server sends 12-byte, space-padded ASCII headers. STATUS is answered with NEEDINIT
(before INIT), READY or HAVEDATA; INIT carries a bead index and a string (read, not used); POSDATA
carries the cell (9 doubles, lattice vectors as columns), its inverse, the number of atoms (int32)
and the positions (3n doubles); GETFORCE is answered with FORCEREADY, the energy, the number of
atoms, the forces (3n doubles), the virial (9 doubles) and an extra string (int32 length, then its
bytes); EXIT ends the client, and so does the server closing the connection between messages (ASE's
server does that instead of EXIT). Numbers are in the machine's byte order.

Units: the protocol speaks atomic units (bohr, hartree). The input is taken to be in Å and eV unless
length_unit (one input length in Å) and energy_unit (one input energy in eV) say otherwise; Å and eV
are converted to atomic units with the constants of ase.units (CODATA 2014), BOHR_IN_ANGSTROM and
HARTREE_IN_EV below, so that an ASE server and this client convert alike. The virial sent is W of
structmd_get_virial (docs/c-api.md), whose sign is i-PI's: the server's stress is -W / volume.
Atom k of the server is the particle of id k; the cell must be rectangular.

The launcher's `structmd client --ipi` (src/launcher/ipi_client.cpp) implements the same protocol;
tests/python/test_ipi_conformance.py holds both clients to the same answers and refusals.
"""

import socket
import struct
import time
from typing import Any, Mapping, Optional, TextIO, Tuple, Union

import numpy as np

from ._evaluate import DEFAULT_OPTIONS, Evaluation, evaluate, orthorhombic_box
from .constants import STATUS
from .errors import ArgumentError
from .simulation import Simulation

BOHR_IN_ANGSTROM = 0.5291772105638411
HARTREE_IN_EV = 27.211386024367243
HEADER_SIZE = 12
UNIX_SOCKET_PREFIX = "/tmp/ipi_"  # i-PI's and ASE's: unix:NAME is the socket /tmp/ipi_NAME
# The longest INIT string accepted (i-PI's are a few bytes), as the launcher's client: a server
# announcing 2^31 - 1 bytes would otherwise have the client wait for them.
MAX_INIT_LENGTH = 1 << 20
# Seconds to wait for each read from the server: an hour, since i-PI may wait long on its other
# clients between two requests, but not forever on a server gone silent.
DEFAULT_READ_TIMEOUT = 3600.0

Address = Union[str, Tuple[str, int]]


class ProtocolError(ConnectionError):
    """The server broke the i-PI protocol or the connection in the middle of a message."""


def parse_address(address: Address) -> Tuple[int, Union[str, Tuple[str, int]]]:
    """(socket family, socket address) of "host:port", (host, port) or "unix:NAME". Raises
    ArgumentError for an address of another form."""
    if isinstance(address, tuple):
        return socket.AF_INET, (address[0], int(address[1]))
    if address.startswith("unix:"):
        name = address[len("unix:"):]
        if not name:
            raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"], "i-PI address unix:NAME needs a NAME")
        return socket.AF_UNIX, UNIX_SOCKET_PREFIX + name
    host, separator, port = address.rpartition(":")
    if not separator or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"],
                            f"i-PI address {address!r}: expected HOST:PORT or unix:NAME")
    return socket.AF_INET, (host, int(port))


def connect(address: Address, timeout: float) -> socket.socket:
    """A connected socket to the server at address, retrying until timeout seconds have passed: a
    client started beside its server may come up first. Raises ConnectionError when no server
    answered in time, ArgumentError for a malformed address, OSError for other socket failures."""
    family, target = parse_address(address)
    deadline = time.monotonic() + timeout
    while True:
        connection = socket.socket(family, socket.SOCK_STREAM)
        try:
            connection.connect(target)
        except (ConnectionRefusedError, FileNotFoundError) as error:
            connection.close()
            if time.monotonic() >= deadline:
                raise ConnectionError(f"no i-PI server at {address} after {timeout:g} s: {error}") from error
            time.sleep(0.1)
            continue
        except OSError:
            connection.close()
            raise
        if family == socket.AF_INET:
            # Every message is a short request answered at once: no waiting to fill packets.
            connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        return connection


class _Channel:
    def __init__(self, connection: socket.socket, read_timeout: Optional[float] = None) -> None:
        self.connection = connection
        self.read_timeout = read_timeout
        connection.settimeout(read_timeout or None)  # 0 or None: wait forever

    def receive(self, size: int, at_boundary: bool = False) -> bytes:
        """size bytes; b"" when at_boundary and the server closed the connection before the first."""
        chunks = []
        remaining = size
        while remaining > 0:
            try:
                chunk = self.connection.recv(remaining)
            except socket.timeout as error:
                raise ProtocolError(f"no data from the server for {self.read_timeout:g} s (read_timeout)") from error
            if not chunk:
                if at_boundary and remaining == size:
                    return b""
                raise ProtocolError(f"the server closed the connection in the middle of a message "
                                    f"({size - remaining} of {size} bytes)")
            chunks.append(chunk)
            remaining -= len(chunk)
        return b"".join(chunks)

    def header(self) -> Optional[str]:
        raw = self.receive(HEADER_SIZE, at_boundary=True)
        # Only the padding on the right is stripped: "  STATUS" is no header of the protocol.
        return raw.decode("ascii", errors="replace").rstrip(" ") if raw else None

    def doubles(self, count: int) -> np.ndarray:
        return np.frombuffer(self.receive(8 * count), dtype=np.float64).copy()

    def int32(self) -> int:
        value: int = struct.unpack("i", self.receive(4))[0]
        return value

    def send(self, *parts: bytes) -> None:
        self.connection.sendall(b"".join(parts))


def _header(text: str) -> bytes:
    return text.encode("ascii").ljust(HEADER_SIZE)


def run(address: Address, input: Union[str, Mapping[str, Any]], options: Optional[Mapping[str, Any]] = None,
        length_unit: float = 1.0, energy_unit: float = 1.0, connect_timeout: float = 60.0,
        log: Optional[TextIO] = None, read_timeout: Optional[float] = DEFAULT_READ_TIMEOUT) -> int:
    """Loads input (a path, a JSON string or a dict) with options (structmd_create options over
    DEFAULT_OPTIONS), connects to the server at address and answers its requests until EXIT or
    until it closes the connection, or until read_timeout seconds pass without data (None or 0:
    no limit). Returns how many configurations were evaluated. Errors: the
    StructmdError subclass of a failed engine call (e.g. ArgumentError when the server sends another
    number of atoms), ProtocolError, ConnectionError."""
    if not (length_unit > 0.0 and energy_unit > 0.0):
        raise ValueError(f"length_unit and energy_unit must be positive, got {length_unit}, {energy_unit}")
    bohr = BOHR_IN_ANGSTROM / length_unit  # one bohr in input lengths
    hartree = HARTREE_IN_EV / energy_unit  # one hartree in input energies
    with Simulation({**DEFAULT_OPTIONS, **(options or {})}) as sim:
        sim.load(input)  # before connecting, so that a bad input never holds a server waiting
        with connect(address, connect_timeout) as connection:
            return _serve(sim, _Channel(connection, read_timeout), bohr, hartree, log)


def _serve(sim: Simulation, channel: _Channel, bohr: float, hartree: float, log: Optional[TextIO]) -> int:
    initialised, evaluations = False, 0
    result: Optional[Evaluation] = None
    while True:
        message = channel.header()
        if message is None or message == "EXIT":
            if log:
                print(f"structmd i-PI client: {message or 'connection closed'} after {evaluations} "
                      "configurations", file=log)
            return evaluations
        if message == "STATUS":
            state = "HAVEDATA" if result is not None else "READY" if initialised else "NEEDINIT"
            channel.send(_header(state))
        elif message == "INIT":
            channel.int32()  # the bead index
            length = channel.int32()
            if length < 0:
                raise ProtocolError("INIT with a negative length")
            if length > MAX_INIT_LENGTH:
                raise ProtocolError(f"INIT announces a string of {length} bytes, more than the {MAX_INIT_LENGTH} accepted")
            channel.receive(length)  # the initialisation string
            initialised = True
        elif message == "POSDATA":
            cell = channel.doubles(9).reshape(3, 3).T  # rows: lattice vectors
            channel.doubles(9)  # the inverse cell
            count = channel.int32()
            # Refused before the positions are read: a wrong count would have us wait for them.
            if count != sim.num_particles:
                raise ArgumentError(STATUS["STRUCTMD_ERR_ARGUMENT"], f"the input has {sim.num_particles} "
                                    f"particles, but the server sent {count} atoms")
            positions = channel.doubles(3 * count).reshape(count, 3)
            result = evaluate(sim, positions * bohr, orthorhombic_box(cell) * bohr)
            evaluations += 1
        elif message == "GETFORCE":
            if result is None:
                raise ProtocolError("GETFORCE before any POSDATA")
            forces = np.ascontiguousarray(result.forces * (bohr / hartree), dtype=np.float64)
            virial = np.ascontiguousarray(result.virial.T / hartree, dtype=np.float64)
            channel.send(_header("FORCEREADY"), struct.pack("d", result.energy / hartree),
                         struct.pack("i", len(forces)), forces.tobytes(), virial.tobytes(), struct.pack("i", 0))
            result = None
        else:
            raise ProtocolError(f"unknown i-PI message {message!r}")
