"""Loading proof files: the catalogue's and a user's go through the same loader.

A proof file is a Python module (loaded by path, as pytest collects test
files) whose module-level :class:`~lkverify.items.Item` objects are its items.
``PAPER = "aleksandrov2023"`` names the paper; otherwise the file's stem does.
The catalogue's proof files ship inside the installed package as
``lkverify.proofs`` (the repository's ``proofs/`` folder).
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import importlib.resources
import importlib.util
import sys
from pathlib import Path

from .errors import InputError
from .items import Item

__all__ = ["ProofFile", "load_proof_file", "catalogue", "find_items"]


@dataclasses.dataclass(frozen=True)
class ProofFile:
    """A loaded proof module: its paper name and items by name."""

    paper: str
    path: Path
    items: dict
    doc: str = ""


def _proofs_dir() -> Path:
    return Path(str(importlib.resources.files("lkverify.proofs")))


def load_proof_file(path) -> ProofFile:
    """Load a proof file by path.

    Raises
    ------
    InputError
        If the file does not exist, is not a ``.py`` file, fails to import, or declares no item.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file; expected a catalogue name (see `lkverify list`) or a path to a .py proof file")
    if path.suffix != ".py":
        raise InputError(f"{path}: expected a Python proof file ending in .py")
    digest = hashlib.sha1(str(path.resolve()).encode()).hexdigest()[:10]
    modname = f"lkverify_proof_{path.stem}_{digest}"
    if modname in sys.modules:
        module = sys.modules[modname]
    else:
        spec = importlib.util.spec_from_file_location(modname, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[modname] = module
        try:
            spec.loader.exec_module(module)
        except InputError:
            del sys.modules[modname]
            raise
        except Exception as exc:  # noqa: BLE001 - a user's file failing to import is bad input
            del sys.modules[modname]
            raise InputError(f"{path}: the proof file failed to load: {type(exc).__name__}: {exc}") from exc
    paper = getattr(module, "PAPER", path.stem)
    items = {}
    for value in vars(module).values():
        if isinstance(value, Item) and value.name not in items:
            value.paper = paper
            items[value.name] = value
    if not items:
        raise InputError(f"{path}: declares no item; expected module-level Theorem objects")
    return ProofFile(paper, path, items, (module.__doc__ or "").strip())


def catalogue() -> list[ProofFile]:
    """Every proof file shipped with lkverify, in name order."""
    return [load_proof_file(p) for p in sorted(_proofs_dir().glob("*.py")) if p.name != "__init__.py"]


def find_items(spec: str) -> list[Item]:
    """Items named by ``spec``: ``paper.item``, ``paper`` (all its items), a path, or ``path.py::item``.

    Raises
    ------
    InputError
        Unknown names (close names are suggested) or unloadable files.
    """
    path_part, _, item_part = spec.partition("::")
    if path_part.endswith(".py") or "/" in path_part or Path(path_part).is_file():
        pf = load_proof_file(path_part)
        if item_part:
            if item_part not in pf.items:
                raise InputError(f"{spec}: no item {item_part!r} in {path_part}; it has {', '.join(pf.items)}")
            return [pf.items[item_part]]
        return list(pf.items.values())
    files = catalogue()
    names = {f"{pf.paper}.{n}": it for pf in files for n, it in pf.items.items()}
    if spec in names:
        return [names[spec]]
    for pf in files:
        if spec == pf.paper:
            return list(pf.items.values())
    close = difflib.get_close_matches(spec, list(names) + [pf.paper for pf in files], n=3, cutoff=0.5)
    hint = f"; did you mean {', '.join(close)}?" if close else "; see `lkverify list`"
    raise InputError(f"{spec}: unknown item{hint}")
