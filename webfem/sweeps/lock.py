"""The lock of a sweep's output CSV: ``.NAME.csv.lock`` (hidden), held while a sweep writes,
holding its pid, host, start time and signature hash. A second sweep into the same CSV,
identical or not, is refused while the first runs (two writers would mix their rows); a lock
whose process has ended on this host is stale and taken over.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import socket
import time
import uuid
from pathlib import Path

from ..errors import InputError
from ..files import pid_alive, temp_path, write_text

__all__ = ["SweepLock", "signature_hash"]

#: Tokens of the locks this process holds (a lock file of this pid with another token was
#: left behind, e.g. by a Ctrl-C while it was being taken, and is stale).
_HELD: set[str] = set()


def signature_hash(sig: dict) -> str:
    """A short hash of a sweep's signature (what its lock file names)."""
    text = json.dumps(sig, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:12]


class SweepLock:
    """The lock of one output CSV (see the module notes); a context manager.

    Raises :class:`~webfem.errors.InputError` naming the sweep that holds it.
    """

    def __init__(self, csv_path: Path, sig: dict, points: int | None = None):
        self.path = csv_path.with_name(f".{csv_path.name}.lock")
        self.csv_path = csv_path
        self.hash = signature_hash(sig)
        self.info = {"pid": os.getpid(), "host": socket.gethostname(), "time": time.time(),
                     "started": time.strftime("%Y-%m-%d %H:%M:%S"), "signature": self.hash,
                     "model": sig["model"], "parameter": sig["parameter"],
                     "points": points if points is not None else sig["points"]
                     if "points" in sig else len(sig["values"]) * len(sig["series"]),
                     "token": uuid.uuid4().hex}
        self.held = False

    def _create(self) -> bool:
        """Create the lock file whole (written aside, then hard-linked: atomic, and never
        seen half-written); False if it exists."""
        tmp = temp_path(self.path)
        try:
            write_text(tmp, json.dumps(self.info))
            try:
                os.link(tmp, self.path)
            except FileExistsError:
                return False
            except OSError as err:   # file systems without hard links
                if err.errno not in (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP):
                    raise
                try:
                    fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
                except FileExistsError:
                    return False
                with os.fdopen(fd, "w") as fh:
                    fh.write(json.dumps(self.info))
            return True
        finally:
            try:
                tmp.unlink()
            except FileNotFoundError:
                pass

    def _read(self) -> dict | None:
        try:
            return json.loads(self.path.read_text())
        except FileNotFoundError:
            return None
        except (OSError, ValueError):
            return {}

    def _stale(self, other: dict) -> bool:
        if not other:   # unreadable: old enough to be left by a crash?
            try:
                return time.time() - self.path.stat().st_mtime > 60.0
            except OSError:
                return True
        if other.get("host") != self.info["host"]:
            return False   # cannot see that host's processes
        if other.get("pid") == os.getpid():   # this process: held unless it was left behind
            return other.get("token") not in _HELD
        try:
            return not pid_alive(int(other["pid"]), float(other.get("time", 0)) or None)
        except (KeyError, TypeError, ValueError):
            return True

    def _take_over(self, other: dict) -> None:
        """Remove a stale lock, unless another process has just replaced it."""
        aside = self.path.with_name(f"{self.path.name}.stale-{os.getpid()}")
        try:
            os.replace(self.path, aside)
        except FileNotFoundError:
            return
        try:
            now = json.loads(aside.read_text())
        except (OSError, ValueError):
            now = {}
        if now != other and now:   # a fresh lock was renamed: put it back
            try:
                os.link(aside, self.path)
            except OSError:
                pass
        aside.unlink(missing_ok=True)

    def acquire(self) -> None:
        try:
            for _ in range(5):
                if self._create():
                    self.held = True
                    _HELD.add(self.info["token"])
                    return
                other = self._read()
                if other is None:
                    continue
                if not self._stale(other):
                    raise InputError(self._refusal(other))
                self._take_over(other)
        except PermissionError as err:
            raise InputError(f"cannot write in {self.path.parent}: permission denied "
                             f"({err.filename})") from None
        except BaseException:   # e.g. Ctrl-C just after the lock was made: undo it
            self.held = True
            self.release()
            raise
        raise InputError(f"{self.csv_path}: could not take the lock {self.path}; "
                         "another sweep keeps taking it")

    def _refusal(self, other: dict) -> str:
        who = (f"pid {other.get('pid', '?')} on {other.get('host', '?')} since "
               f"{other.get('started', '?')}: {other.get('model', '?')} over "
               f"{other.get('parameter', '?')}, {other.get('points', '?')} points")
        if other.get("signature") == self.hash:
            return (f"{self.csv_path}: this same sweep is already running ({who}); two writers "
                    "would mix their rows: wait for it to end, then run again to resume")
        return (f"{self.csv_path}: another sweep is writing this file ({who}); wait for it to "
                f"end or write elsewhere (if that process is gone, delete {self.path})")

    def release(self) -> None:
        if not self.held:
            return
        self.held = False
        _HELD.discard(self.info["token"])
        if (self._read() or {}).get("token") == self.info["token"]:
            self.path.unlink(missing_ok=True)

    def __enter__(self):
        self.acquire()
        return self

    def __exit__(self, *exc):
        self.release()
