"""The one parallel back-end: tasks run in this process or on Dask (a local cluster of our own, or a given scheduler).

The sweep's chunks, the proved layer's cells and the bare report's items all go through
:func:`run_tasks`; none of them starts processes of its own.  Where the tasks run is said by
an object with the attributes ``scheduler`` and ``workers`` (:class:`Cluster`, or the sweep's
``SweepOptions``):

- ``scheduler="synchronous"`` or ``in_process=True``: one after the other in this process;
- ``scheduler=None`` or ``"local"``: a ``LocalCluster`` of ``workers`` processes (default: one per CPU),
  one thread each, closed when the tasks are done;
- ``scheduler="tcp://host:port"``: a running Dask scheduler with at least one worker.

Results are yielded in completion order, with the task's key, so a caller reports progress as
tasks finish and assembles its output in its own order.

Examples
--------
>>> from lkverify.parallel import Cluster, run_tasks
>>> sorted(run_tasks(pow, {k: (k, 2) for k in range(4)}, Cluster(scheduler="synchronous")))
[(0, 0, None), (1, 1, None), (2, 4, None), (3, 9, None)]
"""

from __future__ import annotations

import dataclasses
import logging
import os
import sys
import time
from collections.abc import Callable, Iterator, Mapping

from .errors import InputError, InternalError

__all__ = ["Cluster", "prepare", "run_tasks"]

#: how long a sweep on a given scheduler waits for its first worker before saying there is none
WORKER_WAIT_SECONDS = 30.0
#: how long it tries to reach a given scheduler before saying it cannot
SCHEDULER_TIMEOUT_SECONDS = 10.0


@dataclasses.dataclass(frozen=True)
class Cluster:
    """Where tasks run: ``scheduler`` None / ``"local"`` / ``"synchronous"`` / an address; ``workers`` of a local cluster.

    >>> Cluster(workers=0)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: workers: expected a positive number of worker processes, got 0; e.g. 2
    """

    scheduler: str | None = None
    workers: int | None = None

    def __post_init__(self):
        if self.workers is not None and (not isinstance(self.workers, int) or self.workers < 1):
            raise InputError(f"workers: expected a positive number of worker processes, got {self.workers!r}; e.g. 2")


def run_tasks(fn: Callable, tasks: Mapping, where, *, in_process: bool = False, shared=None, deadline=None,
              timings: dict | None = None) -> Iterator[tuple]:
    """Run ``fn(*args)`` for every ``key → args`` of ``tasks``; yield ``(key, result, exception)`` as they finish.

    Parameters
    ----------
    fn : callable
        Importable by the workers (a module-level function) unless the tasks run in process.
    tasks : mapping
        key → tuple of arguments, submitted in the mapping's order.
    where : Cluster or SweepOptions
        ``scheduler`` and ``workers`` (see the module's docstring).
    in_process : bool
        Run in this process whatever ``where`` says about the scheduler (a small job: starting a
        cluster would cost more than it saves).
    shared : object, optional
        Passed as the first argument of every call; sent once to every worker (``scatter``).
    deadline : float, optional
        ``time.monotonic()`` value after which no task is started and the unfinished are cancelled
        (their keys are never yielded: the caller reports them as undecided).
    timings : dict, optional
        Receives ``"in process": True`` or ``"cluster start"`` (seconds).

    Yields
    ------
    (key, result, exception)
        ``exception`` is None for a task that returned; a task that raised yields its exception
        and the others go on, except an :class:`~lkverify.errors.InternalError`, which is raised.
    """
    timings = {} if timings is None else timings
    first = () if shared is None else (shared,)
    if in_process or where.scheduler == "synchronous":
        timings["in process"] = True
        for key, args in tasks.items():
            if deadline is not None and time.monotonic() > deadline:
                return
            try:
                result = fn(*first, *args)
            except InternalError:
                raise
            except Exception as exc:   # noqa: BLE001 — the task's failure is the caller's to report
                yield key, None, exc
                continue
            yield key, result, None
        return
    mark = time.monotonic()
    with _client(where) as client:
        timings["cluster start"] = time.monotonic() - mark
        from distributed import as_completed

        if shared is not None:
            first = (client.scatter(shared, broadcast=True),)
        futures = {client.submit(fn, *first, *args, pure=False): key for key, args in tasks.items()}
        remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
        try:
            for fut in as_completed(futures, timeout=remaining):
                if fut.status == "error":
                    exc = fut.exception()
                    if isinstance(exc, InternalError):
                        raise exc
                    yield futures[fut], None, exc
                    continue
                yield futures[fut], fut.result(), None
        except TimeoutError:
            client.cancel(list(futures))


def _start_method() -> str:
    """How a local cluster's worker processes start: ``forkserver`` on Linux, Dask's default ``spawn`` elsewhere.

    A fork server is a fresh interpreter, started once per process by :func:`prepare`: it imports
    :data:`PRELOAD` and forks every worker from its single thread, so the workers start in ~0.1 s
    with those imports done. Forking the caller itself (``fork``) is no faster end to end and not
    safe: the caller may be a long-lived process (a notebook, a test runner) whose threads hold
    locks, whose native thread pools do not survive a fork, and whose memory every worker would
    carry. macOS and Windows keep ``spawn``. ``LKVERIFY_START_METHOD`` (``fork``, ``spawn``,
    ``forkserver``) overrides the choice.
    """
    method = os.environ.get("LKVERIFY_START_METHOD") or ("forkserver" if sys.platform.startswith("linux") else "spawn")
    if method not in ("fork", "spawn", "forkserver"):
        raise InputError(f"LKVERIFY_START_METHOD: expected fork, spawn or forkserver, got {method!r}; unset it for "
                         f"the platform's default")
    return method


#: what the fork server imports before it forks a worker: what every lkverify task needs
PRELOAD = ("distributed", "numpy", "sympy", "lkverify.sweep.evaluate", "lkverify.simulate.dop853")


def prepare(where, *, also: tuple[str, ...] = ()) -> None:
    """Start the fork server now if ``where`` is a local cluster whose workers will fork from one.

    Its imports (:data:`PRELOAD`, then ``also``) run in that process while the caller goes on with
    its own work (a sweep's plan, the report's catalogue), so the cluster starts at once later.
    Nothing happens for a given scheduler, in-process runs, another start method, or when the
    server is already running (the first call's modules stay loaded there).

    >>> prepare(Cluster(scheduler="synchronous"))   # nothing to start
    """
    if getattr(where, "scheduler", None) not in (None, "local") or _start_method() != "forkserver":
        return
    import multiprocessing.forkserver as fs

    fs.set_forkserver_preload([*PRELOAD, *also])   # read when the server starts, not by a running one
    fs.ensure_running()


class _client:
    """A distributed Client: a LocalCluster of our own, or the given scheduler (InputError if unreachable)."""

    def __init__(self, options):
        self.options = options
        self.cluster = self.client = None

    def __enter__(self):
        from distributed import Client, LocalCluster

        for name in ("distributed", "distributed.worker", "distributed.scheduler", "distributed.nanny",
                     "distributed.core", "distributed.http.proxy"):
            logging.getLogger(name).setLevel(logging.ERROR)
        address = self.options.scheduler
        if address in (None, "local"):
            n = self.options.workers or os.cpu_count() or 1
            import dask

            # on Linux the workers fork from a fork server that has imported PRELOAD: ~0.1 s each instead of ~1–2 s
            # importing everything anew (spawn)
            prepare(self.options)
            with dask.config.set({"distributed.worker.multiprocessing-method": _start_method()}):
                self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                            dashboard_address=None)
            self.client = Client(self.cluster)
            return self.client
        try:
            self.client = Client(address, timeout=f"{SCHEDULER_TIMEOUT_SECONDS:g}s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"--scheduler {address}: cannot reach a Dask scheduler there ({type(exc).__name__}: "
                             f"{str(exc).splitlines()[0] if str(exc) else 'no answer'}); expected the address of a "
                             f"running scheduler such as tcp://127.0.0.1:8786 (start one with `dask scheduler`), or "
                             f"omit --scheduler for a local cluster") from None
        try:
            self.client.wait_for_workers(1, timeout=WORKER_WAIT_SECONDS)
        except (OSError, TimeoutError):
            self.client.close()
            raise InputError(f"--scheduler {address}: the scheduler has no workers (none joined in "
                             f"{WORKER_WAIT_SECONDS:g} s); expected a cluster with workers: start some with "
                             f"`dask worker {address}`") from None
        return self.client

    def __exit__(self, *exc):
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        return False
