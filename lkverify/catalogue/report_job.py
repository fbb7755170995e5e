"""The bare report's job: every catalogued item at its defaults, on the one parallel back-end, through the proof cache.

:func:`catalogue_report` runs the items on a local Dask cluster of one worker per CPU (default, when
there are a few items to run and more than one CPU), in this process one after the other (``jobs=1``),
on a local cluster of ``jobs`` workers or on a running scheduler (``scheduler``), via
:func:`lkverify.parallel.run_tasks`; an item whose report is in the proof cache
(:mod:`lkverify.cache`, the key of ``lkverify check ITEM`` at no values) is not run.  The
outputs keep the catalogue's order whatever order the items finish in.
"""

from __future__ import annotations

import os

from ..errors import InputError, InternalError
from .loader import catalogue, proof_module_names

__all__ = ["catalogue_report"]

#: the fewest items to run for which the default report starts a local cluster (fewer: in this process)
AUTO_ITEMS = 4

_ITEMS: dict = {}  # qualified name → item; a worker process fills its own on first use


def _report_one(name: str) -> dict:
    """Run one item at its defaults (in a worker): its cache payload (texts, JSON, holds) — plain data, picklable."""
    from ..cache import report_payload

    if not _ITEMS:  # a fresh worker: load the catalogue once per process
        _ITEMS.update({item.qualified_name: item for pf in catalogue() for item in pf.items.values()})
    return report_payload(_ITEMS[name].run({}))


def _auto_jobs(left: int) -> int:
    """The default number of workers for ``left`` items: one per CPU (at most one per item), or 1 (in process).

    >>> _auto_jobs(1), _auto_jobs(0)
    (1, 1)
    """
    cpus = os.cpu_count() or 1
    return min(cpus, left) if cpus >= 2 and left >= AUTO_ITEMS else 1


def _cached(cache, names) -> dict:
    """name → cached payload of the items of ``names`` in the cache."""
    from ..cache import item_key

    if cache is None:
        return {}
    hits = {n: cache.get(item_key(cache, n)) for n in names}
    return {n: p for n, p in hits.items() if p is not None}


def catalogue_report(*, jobs: int | None = None, scheduler: str | None = None, say=None, cache=None,
                     note=None) -> list[dict]:
    """The payload (:func:`lkverify.cache.report_payload`) of every item at its defaults, in the catalogue's order.

    Parameters
    ----------
    jobs : int, optional
        N ≥ 2: a local Dask cluster of N workers; 1: in this process.  Default: one worker per CPU when
        at least :data:`AUTO_ITEMS` items are to be run and the machine has 2 or more CPUs (the workers are
        forked on Linux and inherit the loaded catalogue), else in this process.
    scheduler : str, optional
        ``tcp://host:port`` of a running Dask scheduler, or ``local``.
    say : callable, optional
        ``say(message, force=False)``, progress lines.
    cache : lkverify.cache.ProofCache, optional
        Read before running an item, written after; None: every item is run.
    note : callable, optional
        ``note(message)``: told how many items came from the cache.

    Raises
    ------
    InputError
        ``jobs`` < 1.
    InternalError
        An item's run raised.
    """
    from ..cache import item_key, report_payload
    from ..parallel import Cluster, prepare, run_tasks

    if jobs is not None and jobs < 1:
        raise InputError(f"--jobs: expected a positive number of worker processes, got {jobs}; e.g. --jobs 2")
    say = say or (lambda msg, force=False: None)
    # the catalogue's names as the last full run of this source found them: when every item is cached, no proof
    # module is imported at all (the names are keyed by the source digest like every entry)
    names_key = cache.key("catalogue", "names") if cache is not None else None
    listed = cache.get(names_key) if cache is not None else None
    names = list(listed["names"]) if listed and isinstance(listed.get("names"), list) else None
    outputs = _cached(cache, names) if names else {}
    if names is None or len(outputs) < len(names):
        if jobs != 1 and scheduler in (None, "local"):
            # the workers' fork server imports the proof packages while this process loads the catalogue too
            prepare(Cluster(scheduler=scheduler, workers=jobs), also=tuple(proof_module_names()))
        todo = [item for pf in catalogue() for item in pf.items.values()]
        _ITEMS.clear()
        _ITEMS.update({item.qualified_name: item for item in todo})
        names = list(_ITEMS)
        outputs = _cached(cache, names)
        if cache is not None:
            cache.put(names_key, {"names": names})
    keys = {n: item_key(cache, n) for n in names}
    if outputs and note:
        note(f"{len(outputs)} of {len(names)} items from the proof cache ({cache.directory}; --no-cache recomputes)")
    left = [n for n in names if n not in outputs]
    if jobs is None and scheduler is None:
        jobs = _auto_jobs(len(left))
    in_process = scheduler in (None, "synchronous") and (jobs is None or jobs == 1)
    # theorems first (their chains are the longest), the examples' short simulations last, so the workers end together
    rank = {"Theorem": 0, "Check": 1}
    start_order = sorted(left, key=lambda n: rank.get(type(_ITEMS[n]).__name__, 2))
    if in_process:
        def fn(name):
            return report_payload(_ITEMS[name].run({}, progress=say))

        tasks = {n: (n,) for n in left}
    else:
        fn, tasks = _report_one, {n: (n,) for n in start_order}
        where = "a Dask scheduler at " + scheduler if scheduler not in (None, "local") else \
            f"a local Dask cluster of {jobs or os.cpu_count() or 1} workers"
        if left:
            say(f"{len(left)} items on {where}", force=True)
    if tasks:
        for name, out, exc in run_tasks(fn, tasks, Cluster(scheduler=None if in_process else scheduler, workers=jobs),
                                        in_process=in_process):
            if exc is not None:
                raise InternalError(f"the report of {name} failed: {type(exc).__name__}: {exc}") from exc
            outputs[name] = out
            if cache is not None:
                cache.put(keys[name], out)
            say(f"item {len(outputs)}/{len(names)} done: {name}", force=True)
    say(f"{len(names)} items done", force=True)
    return [outputs[n] for n in names]
