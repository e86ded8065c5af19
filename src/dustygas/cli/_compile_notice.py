"""What the command line prints while numba compiles kernels (the first run of this code).

numba compiles each kernel the first time it is called and caches the machine code on disk
(:mod:`dustygas._numba_cache`), so the first run of a fresh installation spends minutes compiling
before its first step (the default job's 183-193 kernels took 143-249 s on the two-vCPU test
machines, AMD and Intel, 2026-12-05/07). :func:`compile_notice` listens to numba's
``numba:compile`` events (sent only when a kernel is compiled, not when it is loaded from the
cache) and says so on stderr: a line when compilation starts, one every ``every`` seconds
while it goes on, naming the kernel, and a summary when the command ends.
"""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from typing import Iterator, TextIO

__all__ = ["compile_notice"]


class _Notice:
    def __init__(self, stream: TextIO, every: float):
        self.stream = stream
        self.every = every
        self.depth = 0
        self.count = 0
        self.busy = 0.0  # seconds spent compiling (outermost compilations)
        self.current = ""
        self._since = 0.0
        self._lock = threading.Lock()
        self._ticker: threading.Thread | None = None
        self._done = threading.Event()

    def say(self, text: str) -> None:
        with contextlib.suppress(Exception):
            print(f"dustygas: {text}", file=self.stream, flush=True)

    def on_start(self, event) -> None:
        with self._lock:
            if self.count == 0:
                self.say("compiling numba kernels (first run of this code: about 3 to 5 minutes on two cores; "
                         "later runs load them from the cache)")
                self._ticker = threading.Thread(target=self._tick, name="dustygas-compile-notice", daemon=True)
                self._ticker.start()
            if self.depth == 0:
                self._since = time.perf_counter()
                func = getattr((event.data or {}).get("dispatcher"), "py_func", None)
                if func is not None:  # the kernel called from Python, not the functions it inlines
                    self.current = f"{func.__module__.removeprefix('dustygas.')}.{func.__qualname__}"
            self.depth += 1
            self.count += 1

    def on_end(self, event) -> None:
        with self._lock:
            self.depth = max(self.depth - 1, 0)
            if self.depth == 0:
                self.busy += time.perf_counter() - self._since

    def _tick(self) -> None:
        while not self._done.wait(self.every):
            with self._lock:
                if self.depth > 0:
                    elapsed = self.busy + time.perf_counter() - self._since
                    self.say(f"still compiling: {_kernels(self.count)} so far, {elapsed:.0f} s (now {self.current})")

    def close(self) -> None:
        self._done.set()
        if self.count:
            self.say(f"compiled {_kernels(self.count)} in {self.busy:.0f} s (cached for later runs)")


def _kernels(n: int) -> str:
    return f"{n} kernel{'' if n == 1 else 's'}"


@contextlib.contextmanager
def compile_notice(enabled: bool = True, stream: TextIO | None = None, every: float = 15.0) -> Iterator[None]:
    """Report numba compilations on ``stream`` (stderr) while the block runs."""
    if not enabled:
        yield
        return
    from numba.core import event

    notice = _Notice(stream or sys.stderr, every)

    class Listener(event.Listener):
        def on_start(self, ev) -> None:
            notice.on_start(ev)

        def on_end(self, ev) -> None:
            notice.on_end(ev)

    with event.install_listener("numba:compile", Listener()):
        try:
            yield
        finally:
            notice.close()
