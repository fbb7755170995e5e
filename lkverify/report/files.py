"""Output files: refused before any computing when they cannot be written."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from ..errors import InputError

__all__ = ["check_writable_file", "save_figure"]


def check_writable_file(path, *, option: str, suffixes: Sequence[str], note: str = "") -> Path:
    """``path`` as a Path, or InputError (one line, starting with ``option``) if it cannot be written.

    Refused: a name not ending in one of ``suffixes``, a directory, a folder that does not exist
    or is not writable, an existing file that is not writable, and a folder where creating a
    file fails although the permissions allow it (``/proc``, a read-only mount, a full disk):
    a probe file is written and removed.

    Examples
    --------
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> check_writable_file(f"{folder}/map.png", option="--plot", suffixes=(".png",)).name
    'map.png'
    >>> check_writable_file(f"{folder}/no/map.png", option="--plot", suffixes=(".png",))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: --plot: the folder .../no of .../no/map.png does not exist; ...
    """
    path = str(path)
    if not path.lower().endswith(tuple(suffixes)):
        raise InputError(f"{option}: expected a file name ending in {', '.join(suffixes)}{note}, got {path}")
    p = Path(path)
    if p.is_dir():
        raise InputError(f"{option}: expected a file name, got the directory {path}; pass e.g. "
                         f"{p / ('output' + suffixes[0])}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        what = "is not a directory" if parent.exists() else "does not exist"
        raise InputError(f"{option}: the folder {parent} of {path} {what}; expected an existing folder; "
                         f"create it first (mkdir -p {parent}) or write elsewhere")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option}: the folder {parent} is not writable; expected a folder you can write to")
    if p.exists() and not os.access(p, os.W_OK):
        raise InputError(f"{option}: {path} exists and is not writable; expected a writable file")
    probe = parent / f".{p.name}.probe"
    try:                                  # permissions are not all: /proc, a read-only mount, a full disk
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as exc:
        raise InputError(f"{option}: cannot write in the folder {parent} ({exc.strerror or exc}); expected a "
                         f"folder you can write to") from None
    return p


def save_figure(fig, path, *, dpi: int = 110) -> None:
    """Write a matplotlib figure; in an SVG the text stays text (editable, searchable), not paths.

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt, pathlib, tempfile
    >>> fig, ax = plt.subplots(); _ = ax.set_title("δ(ε) certified")
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "f.svg"
    >>> save_figure(fig, path); plt.close(fig)
    >>> "δ(ε) certified" in path.read_text(encoding="utf-8")
    True
    """
    import matplotlib

    with matplotlib.rc_context({"svg.fonttype": "none"}):
        fig.savefig(path, dpi=dpi)
