"""The one network step: connecting to a Dask scheduler, explicitly and under one deadline.

**A scheduler is code.**  Dask pickles what a client, its scheduler and its workers send
each other, and unpickles what it receives: connecting to a scheduler trusts it, and
whoever controls its address, with code execution in this process.  So:

* frictionlaws connects only to an address the user names (the ``scheduler`` argument
  of the API, ``--scheduler ADDRESS`` on the command line); no environment variable
  connects (``FRICTIONLAWS_SCHEDULER`` is not read);
* before the ``distributed.Client`` is made, :func:`connect_scheduler` identifies the
  peer itself, reading its handshake and its reply to an ``identity`` request as
  bytes: Dask's framing, then msgpack with no extension types.  Nothing the peer sends
  there is deserialised: a peer that sends serialised Python objects (pickles, or Dask's
  markers for them) is refused unread, as is one that is not Dask or not a scheduler;
* the first connection to an address in a process warns that the scheduler is
  trusted with code execution;
* ``tls://`` addresses use Dask's security settings (certificates from the Dask
  configuration ``distributed.comm.tls.*``, or a ``distributed.Security``), for the
  identification and for the client alike.

``distributed.Client(address, timeout=...)`` bounds the TCP connection but then waits
for the peer's handshake without a limit; here one deadline covers connection,
handshake and identification, and the error names what failed: no connection, no
handshake, not Dask, serialised objects, not a scheduler.  The client is then made
with the time that is left.
"""

from __future__ import annotations

import importlib
import pickle
import socket
import ssl
import struct
import sys
import time
import warnings
from typing import Any

from ..base.errors import InputError

__all__ = ["CONNECT_TIMEOUT", "connect_scheduler", "TRUST_NOTE", "SCHEMES"]

#: The deadline of connecting to a scheduler, handshake included [s].
CONNECT_TIMEOUT = 10.0

#: Address schemes a scheduler is identified over before it is trusted (``inproc://``, a
#: cluster inside this process, has no peer to identify).
SCHEMES = ("tcp", "tls")

#: What connecting to a scheduler means (the warning of the first connection).
TRUST_NOTE = ("a Dask scheduler and its workers are trusted with code execution in this "
              "process (Dask exchanges pickles); connect only to a cluster you control")

#: Largest message read while identifying a peer [bytes], and most frames in it.
_MAX_MESSAGE = 16 * 2**20
_MAX_FRAMES = 64
#: Deepest nesting of a message read while identifying a peer.
_MAX_DEPTH = 32
#: Dask's markers for objects it deserialises (pickles, serialised data, enum imports).
_OBJECT_MARKERS = ("__Pickled__", "__Serialized__", "__Enum__")

_trusted: set[str] = set()


class _Refused(Exception):
    """The peer is not a Dask scheduler that may be connected to (the reason)."""


def _recv(sock: socket.socket, n: int, deadline: float) -> bytes:
    """Exactly ``n`` bytes from ``sock`` before ``deadline`` (TimeoutError, or _Refused
    when the peer closes first)."""
    out = bytearray()
    while len(out) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(min(n - len(out), 2**20))
        if not chunk:
            raise _Refused("closed the connection without a Dask message")
        out += chunk
    return bytes(out)


def _framed(payload: bytes) -> bytes:
    """One msgpack frame in Dask's framing (its total length, the frame count, lengths)."""
    prelude = struct.pack("QQ", 1, len(payload))
    return struct.pack("Q", len(prelude) + len(payload)) + prelude + payload


def _read_message(sock: socket.socket, deadline: float) -> Any:
    """One Dask message read as bytes and decoded as plain msgpack; nothing is unpickled.

    Raises
    ------
    _Refused
        Not Dask's framing, serialised objects, extension types or too deep a message.
    """
    (size,) = struct.unpack("Q", _recv(sock, 8, deadline))
    if not 16 <= size <= _MAX_MESSAGE:
        raise _Refused(f"did not answer in the Dask protocol (a message of {size} bytes "
                       "announced)")
    body = _recv(sock, size, deadline)
    (count,) = struct.unpack_from("Q", body)
    if not 1 <= count <= _MAX_FRAMES or 8 * (count + 1) > size:
        raise _Refused("did not answer in the Dask protocol (no frames)")
    lengths = struct.unpack_from(f"{count}Q", body, 8)
    if count > 1 or sum(lengths) > size:  # frames beyond the first carry serialised data
        raise _Refused("sent serialised Python objects (pickles) where a Dask scheduler "
                       "sends plain msgpack; refused unread")
    start = 8 * (count + 1)
    return _decode(body[start:start + lengths[0]])


def _msgpack() -> Any:
    """msgpack (a dependency of distributed; untyped library: Any)."""
    return importlib.import_module("msgpack")


def _decode(frame: bytes) -> Any:
    """A msgpack frame as plain Python values: extension types and Dask's object markers
    are refused, never decoded."""
    msgpack = _msgpack()

    def no_ext(code: int, data: bytes) -> Any:
        raise _Refused(f"sent a msgpack extension type ({code}) where a Dask scheduler "
                       "sends plain values; refused unread")

    try:
        value = msgpack.unpackb(frame, raw=False, strict_map_key=False, ext_hook=no_ext,
                                use_list=False)  # tuples: keys may be arrays, as in Dask
    except _Refused:
        raise
    except Exception as exc:  # noqa: BLE001 - any undecodable frame: not Dask
        raise _Refused(f"did not answer in the Dask protocol ({type(exc).__name__})"
                       ) from None
    _check_plain(value, 0)
    return value


def _check_plain(value: Any, depth: int) -> None:
    if depth > _MAX_DEPTH:
        raise _Refused("sent a message nested too deep for a Dask handshake")
    if isinstance(value, dict):
        if any(k in value for k in _OBJECT_MARKERS):
            raise _Refused("sent serialised Python objects (pickles) in its handshake, "
                           "where a Dask scheduler sends plain values; refused unread, "
                           "nothing of it was deserialised")
        for k, v in value.items():
            _check_plain(k, depth + 1)
            _check_plain(v, depth + 1)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _check_plain(v, depth + 1)


class _Unreachable(Exception):
    """No connection (the reason)."""


def _open(scheme: str, host: str, port: int, security: Any, deadline: float
          ) -> socket.socket:
    """A connected socket (wrapped in TLS for ``tls://``); _Unreachable naming why not."""
    try:
        sock = socket.create_connection((host, port),
                                        timeout=max(deadline - time.monotonic(), 0.01))
    except OSError as exc:
        raise _Unreachable("no answer" if isinstance(exc, TimeoutError) else (
            exc.strerror or type(exc).__name__)) from None
    if scheme != "tls":
        return sock
    context = security.get_connection_args("client")["ssl_context"]
    try:
        sock.settimeout(max(deadline - time.monotonic(), 0.01))
        return context.wrap_socket(sock, server_hostname=host)
    except ssl.SSLError as exc:
        sock.close()
        raise _Unreachable(f"the TLS handshake failed: {exc.reason or exc}") from None
    except BaseException:
        sock.close()
        raise


def _identify(scheme: str, host: str, port: int, security: Any, deadline: float
              ) -> dict[str, Any]:
    """Handshake and ``identity`` request, read as bytes: the peer's identity."""
    sock = _open(scheme, host, port, security, deadline)
    try:
        hello = {"compression": None, "python": list(sys.version_info[:3]),
                 "pickle-protocol": pickle.HIGHEST_PROTOCOL}
        msgpack = _msgpack()
        sock.sendall(_framed(msgpack.packb(hello, use_bin_type=True)))
        theirs = _read_message(sock, deadline)
        if not isinstance(theirs, dict) or "pickle-protocol" not in theirs:
            raise _Refused("did not answer in the Dask protocol (no Dask handshake)")
        sock.sendall(_framed(msgpack.packb({"op": "identity", "reply": True},
                                           use_bin_type=True)))
        reply = _read_message(sock, deadline)
    finally:
        sock.close()
    return reply if isinstance(reply, dict) else {"type": type(reply).__name__}


def _security(scheme: str, security: Any, where: str) -> Any:
    """The Dask security settings to use (``security``, or those of the Dask config)."""
    from distributed.security import Security

    sec = Security() if security is None else security
    if scheme == "tls" and sec.get_connection_args("client")["ssl_context"] is None:
        raise InputError(
            f"{where} is a tls:// address but Dask's TLS settings are not given: set the "
            "CA file, client certificate and key in the Dask configuration "
            "(distributed.comm.tls.ca-file, distributed.comm.tls.client.cert, "
            "distributed.comm.tls.client.key) or pass a distributed.Security")
    if scheme != "tls" and sec.require_encryption:
        raise InputError(f"{where} is not a tls:// address, and Dask's configuration "
                         "requires encryption (distributed.comm.require-encryption)")
    return sec


def _address(address: Any, where: str) -> tuple[str, str, int]:
    """(scheme, host, port) of a scheduler address; InputError for anything else."""
    from distributed.comm.addressing import parse_address, parse_host_port

    if not isinstance(address, str) or not address.strip():
        raise InputError(f"{where} is not an address (expected tcp://HOST:PORT or "
                         "tls://HOST:PORT)")
    try:
        scheme, location = parse_address(address)
        if scheme == "inproc":  # this process's own cluster: no peer to identify
            return scheme, location, 0
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(f"{where} is not a valid address ({str(exc)[:200]})") from None
    if scheme not in SCHEMES:
        raise InputError(f"{where}: the scheme {scheme}:// is not supported (expected "
                         "tcp:// or tls://, whose peer is identified before it is trusted)")
    return scheme, host, int(port)


def _probe(address: str, timeout: float, security: Any) -> Any:
    """The security settings, once a Dask scheduler has answered at ``address`` in time;
    :class:`InputError` naming the cause otherwise."""
    where = f"the Dask scheduler address {address!r}"
    scheme, host, port = _address(address, where)
    sec = _security(scheme, security, where)
    if scheme == "inproc":
        return sec
    deadline = time.monotonic() + timeout
    try:
        reply = _identify(scheme, host, port, sec, deadline)
    except _Unreachable as exc:
        raise InputError(f"cannot reach {where} ({exc} within {timeout:g} s)") from None
    except TimeoutError:
        raise InputError(f"{where} accepted the connection but gave no Dask handshake "
                         f"within {timeout:g} s: not a Dask scheduler, or a stalled one"
                         ) from None
    except _Refused as exc:
        raise InputError(f"{where} {exc}: not a Dask scheduler") from None
    except OSError as exc:  # the connection broke during the exchange
        raise InputError(f"{where} broke off the Dask handshake ("
                         f"{exc.strerror or type(exc).__name__}): not a Dask scheduler, or "
                         "a failing one") from None
    if reply.get("type") != "Scheduler":
        raise InputError(f"{where} answered, but as {str(reply.get('type'))[:40]!r}, "
                         "not as a Dask scheduler")
    return sec


def connect_scheduler(address: str, timeout: float | None = None, *,
                      security: Any = None) -> Any:
    """A ``distributed.Client`` connected to ``address``, within one overall deadline.

    The peer is identified first without deserialising anything it sends (module
    notes); the first connection to an address warns that the scheduler is trusted
    with code execution.

    Parameters
    ----------
    address : str
        The scheduler's address (``tcp://host:8786`` or ``tls://host:8786``), named by
        the user: connecting to it trusts it with code execution in this process.
    timeout : float, optional
        The deadline [s] of the whole step (default :data:`CONNECT_TIMEOUT`).
    security : distributed.Security, optional
        TLS settings; default those of the Dask configuration
        (``distributed.comm.tls.*``).

    Returns
    -------
    distributed.Client

    Raises
    ------
    InputError
        Naming the cause: dask.distributed not installed, no connection, no handshake
        (a peer that is not Dask, or stalled), serialised objects in the handshake, a
        peer that is not a scheduler, a ``tls://`` address without TLS settings.
    """
    limit = CONNECT_TIMEOUT if timeout is None else float(timeout)
    try:
        from dask.distributed import Client
    except ImportError:
        raise InputError("a Dask scheduler was given but dask.distributed is not installed "
                         "(install the 'dask' extra: pip install 'frictionlaws[dask]')"
                         ) from None
    start = time.monotonic()
    sec = _probe(address, limit, security)
    if address not in _trusted:
        _trusted.add(address)
        warnings.warn(f"connecting to the Dask scheduler at {address}: {TRUST_NOTE}",
                      UserWarning, stacklevel=2)
    left = max(limit - (time.monotonic() - start), 1.0)
    try:
        return Client(address, timeout=f"{left:.3f}s", security=sec)
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError(f"cannot reach the Dask scheduler at {address!r} "
                         f"({str(exc)[:200]})") from None
