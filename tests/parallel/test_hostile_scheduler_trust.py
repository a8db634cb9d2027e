"""A scheduler is code: it is connected to only by an explicit act, identified without
deserialising anything it sends, and over ``tls://`` with Dask's TLS settings.

* a hostile peer on 127.0.0.1 that answers with a pickle whose unpickling would write a
  marker file: the marker never appears, the command exits 2 with one line;
* the same pickle in the reply to the identity request, a msgpack extension type, a
  peer that is not Dask or is a worker: refused, naming why;
* ``FRICTIONLAWS_SCHEDULER`` alone never connects (``process`` included);
* a real TLS scheduler on 127.0.0.1 with certificates made here (openssl): the work
  runs there with Dask's TLS settings; without them, or with another CA, it is refused;
* the help, the security page and the first connection say a scheduler is trusted
  with code execution.
"""

from __future__ import annotations

import pickle
import shutil
import socket
import struct
import subprocess
import warnings
from collections.abc import Iterator
from pathlib import Path

import pytest
from hostile import Snapshot, check_outcome, run_cli, tcp_peer

pytest.importorskip("distributed")
msgpack = pytest.importorskip("msgpack")

ROOT = Path(__file__).resolve().parents[2]
SECURITY_PAGE = ROOT / "docs" / "user-guide" / "security.rst"


class _Marker:
    """Unpickling this writes a file (what a hostile peer's pickle would do)."""

    def __init__(self, path: Path) -> None:
        self.path = str(path)

    def __reduce__(self):  # noqa: ANN204 - pickle protocol
        return (Path.write_text, (Path(self.path), "code ran"))


def _framed(*frames: bytes) -> bytes:
    body = struct.pack(f"Q{len(frames)}Q", len(frames), *map(len, frames)) + b"".join(frames)
    return struct.pack("Q", len(body)) + body


def _pickled(marker: Path) -> bytes:
    """A Dask message whose deserialisation unpickles :class:`_Marker`."""
    head = msgpack.packb({"__Pickled__": 1})
    sub = msgpack.packb({"pickled-obj": pickle.dumps(_Marker(marker)), "num-sub-frames": 0})
    return _framed(head, sub)


def _inline_marker(marker: Path) -> bytes:
    """The marker in one frame, Dask's ``__Pickled__`` key pointing at itself."""
    return _framed(msgpack.packb({"compression": None, "pickle-protocol": 5,
                                  "x": {"__Pickled__": 0},
                                  "obj": pickle.dumps(_Marker(marker))}))


HANDSHAKE = _framed(msgpack.packb({"compression": None, "python": [3, 12, 0],
                                   "pickle-protocol": 5}))


@pytest.fixture
def campaign_csv(tmp_path: Path) -> Path:
    data = tmp_path / "d.csv"
    data.write_text("mu,p [MPa],surface\n" + "".join(
        f"0.{6 - i},0.0{i + 3},{s}\n" for s in ("a", "b") for i in range(4)), encoding="utf-8")
    return data


def _hostile_run(tmp_path: Path, data: Path, replies: list[bytes]) -> tuple[str, Path]:
    marker = tmp_path / "MARKER"
    replies = [r.replace(b"@@", b"") for r in replies]
    gen = tcp_peer(replies)
    address = next(gen)
    try:
        snap = Snapshot.take([tmp_path], inputs=[data])
        res = run_cli(["fit", "--law", "thirion", str(data), "--by", "surface",
                       "--scheduler", address], timeout=20)
        check_outcome(res, snapshot=snap, codes=[2])
    finally:
        gen.close()
    return res.err, marker


@pytest.mark.hostile
@pytest.mark.parametrize("where", ["handshake", "identity reply", "inline"])
def test_a_peer_that_sends_a_pickle_runs_no_code(tmp_path: Path, campaign_csv: Path,
                                                 where: str) -> None:
    marker = tmp_path / "MARKER"
    replies = {"handshake": [_pickled(marker)],
               "identity reply": [HANDSHAKE, _pickled(marker)],
               "inline": [_inline_marker(marker)]}[where]
    err, _ = _hostile_run(tmp_path, campaign_csv, replies)
    assert not marker.exists(), "the peer's pickle was unpickled: its code ran"
    assert "serialised Python objects" in err and "not a Dask scheduler" in err, err


@pytest.mark.hostile
@pytest.mark.parametrize(("replies", "said"), [
    ([_framed(msgpack.packb(msgpack.ExtType(5, b"x")))], "extension type"),
    ([HANDSHAKE, _framed(msgpack.packb({"type": "Worker"}))], "not as a Dask scheduler"),
    ([b"HTTP/1.1 400 Bad Request\r\n\r\n" * 4], "not answer in the Dask protocol"),
    ([_framed(msgpack.packb([1, 2]))], "no Dask handshake"),
    ([HANDSHAKE, _framed(b"\xc1")], "not answer in the Dask protocol"),
])
def test_a_peer_that_is_not_a_dask_scheduler_is_named(tmp_path: Path, campaign_csv: Path,
                                                      replies: list[bytes], said: str) -> None:
    err, _ = _hostile_run(tmp_path, campaign_csv, replies)
    assert said in err, err


@pytest.mark.hostile
def test_the_environment_alone_connects_to_nothing(tmp_path: Path, small_campaign: Path,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """``process`` with FRICTIONLAWS_SCHEDULER naming a hostile peer: no connection is
    made at all (the peer never sees a byte), the records are processed here."""
    marker = tmp_path / "MARKER"
    gen = tcp_peer([_pickled(marker)])
    address = next(gen)
    try:
        with socket.create_connection(("127.0.0.1", int(address.rsplit(":", 1)[1]))):
            pass  # the peer is up
        monkeypatch.setenv("FRICTIONLAWS_SCHEDULER", address)
        out = tmp_path / "out.csv"
        res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig",
                       str(small_campaign / "rig.toml"), "-o", str(out), "--jobs", "1"])
    finally:
        gen.close()
    check_outcome(res)
    assert res.code == 0 and out.exists() and not marker.exists()
    assert "FRICTIONLAWS_SCHEDULER is set but is not read" in res.err


def test_the_help_and_the_security_page_say_a_scheduler_is_trusted_with_code() -> None:
    for argv in (["fit", "--help"], ["compare", "--help"], ["process", "--help"]):
        res = run_cli(argv)
        text = " ".join(res.out.split())
        assert "trusted with code execution" in text and "FRICTIONLAWS_SCHEDULER is not read" \
            in text, argv
    page = " ".join(SECURITY_PAGE.read_text(encoding="utf-8").split())
    for words in ("trusted with code execution", "tls://", "distributed.comm.tls.ca-file",
                  "FRICTIONLAWS_SCHEDULER", "never unpickled"):
        assert words in page, words


# ------------------------------------------------------------------ a real TLS scheduler


def _certificates(where: Path) -> tuple[Path, Path]:
    """A self-signed certificate for 127.0.0.1 (its own CA) and its key, made with openssl."""
    if shutil.which("openssl") is None:
        pytest.skip("openssl is not installed")
    cert, key = where / "cert.pem", where / "key.pem"
    subprocess.run(["openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt",
                    "ec_paramgen_curve:prime256v1", "-nodes", "-keyout", str(key), "-out",
                    str(cert), "-days", "1", "-subj", "/CN=127.0.0.1",
                    "-addext", "subjectAltName=IP:127.0.0.1",
                    "-addext", "basicConstraints=critical,CA:TRUE"],
                   check=True, capture_output=True, timeout=30)
    return cert, key


@pytest.fixture(scope="module")
def tls_cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, dict]]:
    import dask
    import distributed
    from distributed.security import Security

    cert, key = _certificates(tmp_path_factory.mktemp("tls"))
    sec = Security(tls_ca_file=str(cert), tls_scheduler_cert=str(cert),
                   tls_scheduler_key=str(key), tls_worker_cert=str(cert),
                   tls_worker_key=str(key), tls_client_cert=str(cert),
                   tls_client_key=str(key), require_encryption=True)
    settings = {"distributed.comm.tls.ca-file": str(cert),
                "distributed.comm.tls.client.cert": str(cert),
                "distributed.comm.tls.client.key": str(key)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with dask.config.set({"distributed.worker.profile.enabled": False}), \
                distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                         protocol="tls://", host="127.0.0.1",
                                         security=sec, dashboard_address=None) as cluster:
            yield cluster.scheduler_address, settings


def test_a_tls_scheduler_runs_the_work_with_daskss_tls_settings(
        tls_cluster: tuple[str, dict], campaign_csv: Path) -> None:
    import dask

    from frictionlaws.parallel import run_parallel

    address, settings = tls_cluster
    assert address.startswith("tls://127.0.0.1:")
    with dask.config.set(settings), pytest.warns(UserWarning,
                                                 match="trusted with code execution"):
        assert run_parallel(abs, [-1, -2, 3], scheduler=address) == [1, 2, 3]
    with dask.config.set(settings):
        remote = run_cli(["fit", "--law", "thirion", str(campaign_csv), "--by", "surface",
                          "--scheduler", address, "--json"], timeout=60)
    local = run_cli(["fit", "--law", "thirion", str(campaign_csv), "--by", "surface",
                     "--json"])
    check_outcome(remote, json_out=True)
    assert remote.code == 0 and remote.out == local.out


def test_a_tls_scheduler_without_tls_settings_or_with_another_ca_is_refused(
        tls_cluster: tuple[str, dict], tmp_path: Path) -> None:
    import dask

    from frictionlaws.base.errors import InputError
    from frictionlaws.parallel import run_parallel

    address, settings = tls_cluster
    with pytest.raises(InputError, match="Dask's TLS settings are not given"):
        run_parallel(abs, [1], scheduler=address)
    other, other_key = _certificates(tmp_path)
    with dask.config.set({"distributed.comm.tls.ca-file": str(other),
                          "distributed.comm.tls.client.cert": str(other),
                          "distributed.comm.tls.client.key": str(other_key)}), \
            pytest.raises(InputError, match="TLS handshake failed"):
        run_parallel(abs, [1], scheduler=address)
    with pytest.raises(InputError, match="requires encryption"), \
            dask.config.set({"distributed.comm.require-encryption": True}):
        run_parallel(abs, [1], scheduler="tcp://127.0.0.1:9")
