"""The one network step: connecting to a Dask scheduler, under one overall deadline.

``distributed.Client(address, timeout=...)`` bounds the TCP connection, but then waits
for the peer's handshake without a limit: an address that accepts TCP and never
answers (or is not Dask) hangs the process.  :func:`connect_scheduler` first
identifies the peer with the deadline around the whole exchange (connect, handshake,
an ``identity`` request) in a thread of its own, and names what failed: no
connection, no handshake, or a peer that is not a Dask scheduler.  Only then is the
client made, with the time that is left.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import socket
import time
from typing import Any

from ..base.errors import InputError

__all__ = ["CONNECT_TIMEOUT", "connect_scheduler"]

#: The deadline of connecting to a scheduler, handshake included [s].
CONNECT_TIMEOUT = 10.0


async def _identity(address: str, timeout: float) -> dict[str, Any]:
    """Connect, handshake and ask the peer who it is; the reply (a dict) or an error."""
    from distributed.comm import connect

    comm = await connect(address, timeout=timeout)
    try:
        await comm.write({"op": "identity", "reply": True})
        reply = await comm.read()
    finally:
        comm.abort()
    return reply if isinstance(reply, dict) else {"reply": type(reply).__name__}


def _identify(address: str, timeout: float) -> dict[str, Any]:
    """:func:`_identity` run to its end or to the deadline, in a fresh event loop."""
    return asyncio.run(asyncio.wait_for(_identity(address, timeout), timeout))


def _reach(address: str, where: str, timeout: float) -> None:
    """Open and close a TCP connection to a ``tcp://`` address: refused, unknown or silent
    hosts are named here, before any Dask protocol."""
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address)
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(f"{where} is not a valid address ({str(exc)[:200]})") from None
    if scheme != "tcp":
        return
    try:
        socket.create_connection((host, port), timeout=timeout).close()
    except OSError as exc:
        reason = "no answer" if isinstance(exc, TimeoutError) else (
            exc.strerror or type(exc).__name__)
        raise InputError(f"cannot reach {where} ({reason} within {timeout:g} s)") from None


def _probe(address: str, timeout: float) -> None:
    """Raise :class:`InputError` naming the cause unless a Dask scheduler answers in time."""
    where = f"the Dask scheduler address {address!r}"
    limit, start = timeout, time.monotonic()
    _reach(address, where, timeout)
    timeout = max(timeout - (time.monotonic() - start), 0.5)
    pool = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="frictionlaws-probe")
    try:
        reply = pool.submit(_identify, address, timeout).result(timeout + 1.0)
    except (TimeoutError, asyncio.TimeoutError, concurrent.futures.TimeoutError):
        raise InputError(f"{where} accepted the connection but gave no Dask handshake "
                         f"within {limit:g} s: not a Dask scheduler, or a stalled one"
                         ) from None
    except OSError as exc:
        raise InputError(f"cannot reach {where} ({str(exc)[:200]})") from None
    except (ValueError, TypeError) as exc:
        raise InputError(f"{where} is not a valid address ({str(exc)[:200]})") from None
    except Exception as exc:  # noqa: BLE001 - a non-Dask peer's bytes fail in many ways
        raise InputError(f"{where} did not answer in the Dask protocol: not a Dask "
                         f"scheduler ({type(exc).__name__}: {str(exc)[:80]})") from None
    finally:
        pool.shutdown(wait=False)
    if reply.get("type") != "Scheduler":
        raise InputError(f"{where} answered, but as {str(reply.get('type'))[:40]!r}, "
                         "not as a Dask scheduler")


def connect_scheduler(address: str, timeout: float | None = None) -> Any:
    """A ``distributed.Client`` connected to ``address``, within one overall deadline.

    Parameters
    ----------
    address : str
        The scheduler's address (``tcp://host:8786``).
    timeout : float, optional
        The deadline [s] of the whole step (default :data:`CONNECT_TIMEOUT`).

    Returns
    -------
    distributed.Client

    Raises
    ------
    InputError
        Naming the cause: dask.distributed not installed, no connection, no handshake
        (a peer that is not Dask, or stalled), a peer that is not a scheduler.
    """
    limit = CONNECT_TIMEOUT if timeout is None else float(timeout)
    try:
        from dask.distributed import Client
    except ImportError:
        raise InputError("a Dask scheduler was given but dask.distributed is not installed "
                         "(install the 'dask' extra: pip install 'frictionlaws[dask]')"
                         ) from None
    start = time.monotonic()
    _probe(address, limit)
    left = max(limit - (time.monotonic() - start), 1.0)
    try:
        return Client(address, timeout=f"{left:.3f}s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError(f"cannot reach the Dask scheduler at {address!r} "
                         f"({str(exc)[:200]})") from None
