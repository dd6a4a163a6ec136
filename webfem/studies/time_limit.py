"""A time limit on a block of Python code, in the main thread (SIGALRM) or in any other
(a Dask worker's: an asynchronous exception), raised again until the block ends: each design
point of a campaign is solved under one (:mod:`webfem.studies.fit_campaign`).

Examples
--------
>>> with time_limit(None) as limit:    # no limit
...     pass
>>> limit.expired
False
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager

__all__ = ["time_limit", "TimeLimit"]


class TimeLimit:
    """What :func:`time_limit` yields: ``expired`` once the time is up (an exception raised
    in the meantime, whatever its type, is the limit's: library code that catches errors
    may turn the TimeoutError into another)."""

    __slots__ = ("seconds", "expired")

    def __init__(self, seconds: float | None):
        self.seconds, self.expired = seconds, False

    @property
    def message(self) -> str:
        return f"no answer within {self.seconds:g} s"


#: After the limit, the TimeoutError is raised again this often [s] until the block ends
#: (code that catches every error would otherwise swallow it and go on without a limit).
_AGAIN_S = 1.0


@contextmanager
def time_limit(seconds: float | None):
    """Raise TimeoutError in the calling thread after ``seconds`` (again every
    :data:`_AGAIN_S` until the block ends); yields a :class:`TimeLimit`. No limit where the
    platform has neither SIGALRM nor CPython's asynchronous exceptions.

    In the main thread (a serial campaign, a local worker process) by SIGALRM. A Dask
    worker solves in a thread of its own, which signals never reach: there a timer thread
    raises the error into it (``PyThreadState_SetAsyncExc``). Either way Python raises it
    between bytecodes, so a long call into compiled code (a sparse factorisation) ends
    first: the two limits behave alike."""
    limit = TimeLimit(seconds)
    if not seconds:
        yield limit
    elif threading.current_thread() is not threading.main_thread():
        with _thread_time_limit(limit):
            yield limit
    elif not hasattr(signal, "SIGALRM"):
        yield limit
    else:
        def stop(signum, frame):
            limit.expired = True
            raise TimeoutError(limit.message)
        old = signal.signal(signal.SIGALRM, stop)
        try:        # armed inside: the clean-up runs however soon the limit strikes
            signal.setitimer(signal.ITIMER_REAL, seconds, _AGAIN_S)
            yield limit
        finally:
            _despite_timeouts(lambda: (signal.setitimer(signal.ITIMER_REAL, 0),
                                       signal.signal(signal.SIGALRM, old)))


def _despite_timeouts(step) -> None:
    """``step()`` to its end, though a timeout raised meanwhile interrupts it: the clean-up
    of a limit must not be cut short by the limit (the error already on its way is the one
    the caller sees)."""
    while True:
        try:
            step()
            return
        except TimeoutError:
            continue


class _Timeout(TimeoutError):
    """The TimeoutError raised into a thread (raised as its class, without arguments)."""

    limit: TimeLimit

    def __str__(self) -> str:
        return self.limit.message


@contextmanager
def _thread_time_limit(limit: TimeLimit):
    """:func:`time_limit` in a thread other than the main one."""
    try:
        import ctypes
        set_async = ctypes.pythonapi.PyThreadState_SetAsyncExc
    except (ImportError, AttributeError):     # not CPython: no limit
        yield
        return
    ident = ctypes.c_ulong(threading.get_ident())
    error = type("TimeoutError", (_Timeout,), {"limit": limit})   # carries the message
    guard = threading.Lock()
    ended = threading.Event()
    state = {"done": False}

    def watch():
        wait = limit.seconds
        while not ended.wait(wait):
            with guard:          # never after the block has ended
                if state["done"]:
                    return
                limit.expired = True
                set_async(ident, ctypes.py_object(error))
            wait = _AGAIN_S

    def end():
        with guard:
            state["done"] = True
        ended.set()
        # a timeout raised but not yet delivered (the block ended meanwhile) must not
        # surface later in this thread: withdraw it
        set_async(ident, None)

    try:
        threading.Thread(target=watch, daemon=True, name="webfem time limit").start()
        yield
    finally:
        _despite_timeouts(end)
