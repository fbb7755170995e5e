"""The Dask client a sweep or a proved layer runs on: a local cluster of our own, or a given scheduler."""

from __future__ import annotations

import logging
import os

from ..errors import InputError

__all__: list = []

#: how long a sweep on a given scheduler waits for its first worker before saying there is none
WORKER_WAIT_SECONDS = 30.0
#: how long it tries to reach a given scheduler before saying it cannot
SCHEDULER_TIMEOUT_SECONDS = 10.0


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
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
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
