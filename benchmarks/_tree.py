"""Shared by the start-up benchmarks: the environment that times another checkout (``--tree DIR``), the load."""

from __future__ import annotations

import os


def tree_env(tree: str | None) -> dict:
    """This process's environment, with DIR first on PYTHONPATH when ``--tree DIR`` is given.

    >>> tree_env("/tmp/x")["PYTHONPATH"].split(os.pathsep)[0]
    '/tmp/x'
    """
    env = dict(os.environ)
    if tree:
        env["PYTHONPATH"] = os.pathsep.join([os.path.abspath(tree), *filter(None, [env.get("PYTHONPATH")])])
    return env


def load_average() -> float:
    """The 1-minute load average (NaN where the OS does not say)."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
