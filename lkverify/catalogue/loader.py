"""Loading proof files: the catalogue's packages and a user's files go through the same checks.

A proof module's module-level :class:`~lkverify.catalogue.items.Item` objects are its
items.  ``PAPER = "aleksandrov2023"`` names the paper; otherwise the module's name does.

The catalogue's proofs are the packages of :mod:`lkverify.proofs` (the repository's
``proofs/`` folder, installed inside the distribution), one per paper, one module per
theorem, example or audit; the package's ``__init__`` re-exports its items.  They are
imported under their real names (``importlib.import_module("lkverify.proofs.aleksandrov2023")``),
so ``lkverify.proofs.aleksandrov2023.theorem3`` *is* the catalogue's item: one import path
per item.  A user's proof file (a single module) is loaded by path, as pytest collects test
files; a path inside :mod:`lkverify.proofs` is imported under its real name.

A proof file is Python: loading it executes it with the user's permissions,
like any script.  Loading is bounded by a time limit (:data:`LOAD_LIMIT_SECONDS`
unless ``load_limit`` says otherwise; ``lkverify --load-limit``), separate from
the ``--budget`` of the job run afterwards.  A file that calls ``sys.exit``,
does not finish loading in time, declares two items with the same name, or
declares a theorem whose functional or hypotheses use states or symbols its
system does not have is refused with an :class:`~lkverify.errors.InputError`.
Items a user file imports from the catalogue (to build on them) stay the catalogue's:
they are not items of the user's file.
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import importlib
import importlib.util
import pkgutil
import sys
from pathlib import Path

from ..options import LOAD_LIMIT_SECONDS, BudgetExceeded, Deadline
from ..errors import InputError
from .index import PROOFS_PACKAGE, package_of, unknown_item_message

__all__ = ["ProofFile", "load_proof_file", "load_proof_module", "catalogue", "find_items", "LOAD_LIMIT_SECONDS",
           "PROOFS_PACKAGE"]

# LOAD_LIMIT_SECONDS (the default time limit for loading one proof file) is lkverify.options', PROOFS_PACKAGE the
# index's, both re-exported here; this module imports SymPy and the items only where it checks a loaded file, so
# that an unknown name is refused (from the index) without them


@dataclasses.dataclass(frozen=True)
class ProofFile:
    """A loaded proof module: its paper name and items by name.

    Attributes
    ----------
    paper : str
    path : Path
        The module's file (a package's ``__init__.py``).
    items : dict
        Item name → item, in declaration order.
    doc : str
        The module's docstring.

    Examples
    --------
    >>> import pathlib, shutil, tempfile
    >>> d = pathlib.Path(tempfile.mkdtemp()); path = d / "mine.py"
    >>> _ = path.write_text('''"My proof."
    ... from lkverify import Parameters
    ... from lkverify.catalogue import Check
    ... PAPER = "mypaper"
    ... positive = Check("positive", parameters=Parameters(), checks=[])
    ... ''')
    >>> pf = load_proof_file(path)
    >>> pf.paper, pf.path.name, list(pf.items), pf.doc
    ('mypaper', 'mine.py', ['positive'], 'My proof.')
    >>> pf.items["positive"].qualified_name           # the loader set the item's paper
    'mypaper.positive'
    >>> shutil.rmtree(d)
    """

    paper: str
    path: Path
    items: dict
    doc: str = ""


def _proofs_package():
    return importlib.import_module(PROOFS_PACKAGE)


def _proofs_dirs() -> list[Path]:
    return [Path(p).resolve() for p in _proofs_package().__path__]


def load_proof_file(path, *, load_limit: float | None = LOAD_LIMIT_SECONDS) -> ProofFile:
    """Load a proof file by path (this executes it as Python).

    A file inside :mod:`lkverify.proofs` (a catalogue module) is imported under its real
    module name, never a second time under another.

    Parameters
    ----------
    path : str or Path
    load_limit : float or None, keyword-only
        Seconds the import may take (``None``: no limit); enforced with ``SIGALRM``
        in the main thread.

    Raises
    ------
    InputError
        If the file does not exist, is not a ``.py`` file, fails to import, calls
        ``sys.exit`` while loading, does not load within ``load_limit``, declares no
        item, declares two items with the same name, or declares an inconsistent theorem.

    Examples
    --------
    >>> import pathlib, shutil, tempfile
    >>> d = pathlib.Path(tempfile.mkdtemp()); path = d / "mine.py"
    >>> _ = path.write_text('''"My proof."
    ... from lkverify import Parameters
    ... from lkverify.catalogue import Check
    ... PAPER = "mypaper"
    ... positive = Check("positive", parameters=Parameters(), checks=[])
    ... ''')
    >>> load_proof_file(path).items["positive"].run().verdict
    'every check holds'
    >>> _ = (d / "exits.py").write_text("import sys; sys.exit(2)")
    >>> load_proof_file(d / "exits.py")                 # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: .../exits.py: the proof file called sys.exit(2) while loading; expected a file that only declares items; remove the exit call (or guard it with if __name__ == "__main__")
    >>> load_proof_file(d / "notes.txt")                # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: .../notes.txt: no such file; expected a catalogue name (see `lkverify list`) or a path to a .py proof file
    >>> shutil.rmtree(d)
    """
    path = Path(path)
    if not path.is_file():
        what = "is a directory" if path.is_dir() else "no such file"
        raise InputError(f"{path}: {what}; expected a catalogue name (see `lkverify list`) or a path to a .py proof file")
    if path.suffix != ".py":
        raise InputError(f"{path}: expected a Python proof file ending in .py")
    real = _catalogue_module_name(path)
    if real is not None:
        return load_proof_module(real, load_limit=load_limit)
    digest = hashlib.sha1(str(path.resolve()).encode()).hexdigest()[:10]
    modname = f"lkverify_proof_{path.stem}_{digest}"
    if modname in sys.modules:
        module = sys.modules[modname]
    else:
        module = _execute(path, modname, load_limit)
    try:
        return _proof_file(module, path, path.stem, foreign=_catalogue_items())
    except InputError:
        del sys.modules[modname]
        raise


def load_proof_module(name: str, *, load_limit: float | None = LOAD_LIMIT_SECONDS) -> ProofFile:
    """Import a proof module or package by its module name (``"lkverify.proofs.aleksandrov2023"``).

    The same checks as :func:`load_proof_file` (time limit, ``sys.exit``, duplicate names,
    consistency); the module is imported once and stays in ``sys.modules`` under ``name``.

    Raises
    ------
    InputError
        As :func:`load_proof_file`.
    """
    module = sys.modules.get(name)
    if module is None:
        module = _import(name, load_limit)
    path = Path(module.__file__)
    return _proof_file(module, path, name.rpartition(".")[2])


def _catalogue_module_name(path: Path) -> str | None:
    """The real module name of a file inside :mod:`lkverify.proofs`, else None."""
    resolved = path.resolve()
    for root in _proofs_dirs():
        try:
            rel = resolved.relative_to(root)
        except ValueError:
            continue
        parts = list(rel.with_suffix("").parts)
        if parts and parts[-1] == "__init__":
            parts.pop()
        if not parts or not all(p.isidentifier() for p in parts):
            return None
        return ".".join([PROOFS_PACKAGE, *parts])
    return None


def _catalogue_items() -> set:
    """The ids of the items of every catalogue module imported so far (a user file may import them)."""
    from .items import Item

    prefix = PROOFS_PACKAGE + "."
    return {id(v) for name, mod in list(sys.modules.items()) if name.startswith(prefix) and mod is not None
            for v in vars(mod).values() if isinstance(v, Item)}


def _proof_file(module, path: Path, default_paper: str, *, foreign=frozenset()) -> ProofFile:
    """The items of a loaded module (its own, not the ``foreign`` ones), checked."""
    from .items import Item

    paper = getattr(module, "PAPER", default_paper)
    items: dict = {}
    where: dict = {}
    for var, value in vars(module).items():
        if not isinstance(value, Item) or id(value) in foreign:
            continue
        if value.name in items:
            if items[value.name] is value:
                continue  # the same item under two variable names
            raise InputError(f"{path}: two items are named {value.name!r} (variables {where[value.name]} and "
                             f"{var}); expected one name per item; rename one of them")
        items[value.name] = value
        where[value.name] = var
    if not items:
        raise InputError(f"{path}: declares no item; expected module-level Theorem objects")
    for item in items.values():
        problem = _inconsistency(item)
        if problem:
            raise InputError(f"{path}: item {item.name}: {problem}")
    for item in items.values():
        if not item.paper:  # items constructed with paper=... keep it
            item.paper = paper
    return ProofFile(paper, path, items, (module.__doc__ or "").strip())


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def _execute(path: Path, modname: str, load_limit: float | None):
    """Import the file as module ``modname`` within the time limit; every failure is an InputError."""
    spec = importlib.util.spec_from_file_location(modname, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module
    try:
        _guarded(lambda: spec.loader.exec_module(module), path, load_limit)
    except InputError:
        del sys.modules[modname]
        raise
    return module


def _import(name: str, load_limit: float | None):
    """``importlib.import_module(name)`` within the time limit; every failure is an InputError."""
    box = []
    _guarded(lambda: box.append(importlib.import_module(name)), name, load_limit)
    return box[0]


def _guarded(load, where, load_limit: float | None) -> None:
    """Run ``load()`` under the load limit, turning every way a proof file can fail into an InputError."""
    limit = Deadline(load_limit)
    try:
        with limit.enforced():
            load()
    except InputError as exc:  # e.g. a Theorem refused where the file declares it: say which file
        text = _one_line(exc)
        raise InputError(text if text.startswith(str(where)) else f"{where}: {text}") from exc
    except BudgetExceeded:
        raise InputError(f"{where}: the proof file did not finish loading within the load limit of "
                         f"{load_limit:g} s (an endless loop or a long computation at import?); expected a "
                         f"file that only declares items; raise the limit with --load-limit SECONDS") from None
    except SystemExit as exc:
        raise InputError(f"{where}: the proof file called sys.exit({exc.code!r}) while loading; expected a file "
                         f"that only declares items; remove the exit call (or guard it with "
                         f"if __name__ == \"__main__\")") from None
    except Exception as exc:  # noqa: BLE001 - a user's file failing to import is bad input
        raise InputError(f"{where}: the proof file failed to load: {type(exc).__name__}: {_one_line(exc)}") from exc


def _inconsistency(item) -> str | None:
    """Why a theorem cannot be checked as declared (states or symbols its system lacks), else None."""
    import sympy
    from sympy.core.function import AppliedUndef

    from ..declare.symbols import t as t_sym

    system = getattr(item, "system", None)
    if system is None or not hasattr(system, "state_functions"):
        return None
    funcs = system.state_functions()
    params = system.parameters
    declared = set()
    for spec in params:
        declared |= {s for s in spec.symbols if isinstance(s, sympy.Symbol)}
    pairs = [("its functional", getattr(item, "functional", None), system)]
    pairs += [(f"the functional of claim {c.name!r}", getattr(c, "functional", None), getattr(c, "system", None))
              for c in getattr(item, "claims", ())]
    for what, functional, sys_ in pairs:
        problem = _foreign_states(what, functional, sys_)
        if problem:
            return problem
    for h in getattr(item, "hypotheses", ()):
        margin = getattr(h, "margin", None)
        if margin is None:
            margin = getattr(h, "matrix", None)
        try:
            expr = sympy.sympify(margin)
        except (sympy.SympifyError, TypeError):
            continue
        atoms = expr.atoms(AppliedUndef) if isinstance(expr, sympy.Basic) else set()
        states = sorted({str(a.func) for a in atoms if a.func in funcs})
        if states:
            return (f"hypothesis {h.name!r} depends on the state component(s) {', '.join(states)}; expected a "
                    f"condition on the parameters only (a hypothesis is checked once, not along a trajectory); "
                    f"move it into a claim or a bound step")
        free = expr.free_symbols if isinstance(expr, sympy.Basic) else set()
        if t_sym in free:
            return (f"hypothesis {h.name!r} depends on the time t; expected a condition on the constant "
                    f"parameters only; state a condition on a time-varying coefficient for every t in a claim")
        undeclared = sorted(str(s) for s in free - declared
                            if not any(s in getattr(i, "variables", ()) for i in expr.atoms(sympy.Integral)))
        if undeclared:
            return (f"hypothesis {h.name!r} uses the undeclared symbol(s) {', '.join(undeclared)}; expected only "
                    f"parameters of the system ({', '.join(params.names) or 'none declared'}); declare them "
                    f"with Parameters().scalar(...) or use a declared parameter")
    return None


def _foreign_states(what: str, functional, system) -> str | None:
    """Why ``functional`` uses a state function that ``system`` does not have, else None."""
    import sympy
    from sympy.core.function import AppliedUndef

    if functional is None or system is None or not hasattr(system, "state_functions"):
        return None
    expr = functional.expr
    if not isinstance(expr, sympy.Basic):
        return None
    funcs = system.state_functions()
    foreign = sorted({str(a.func) for a in expr.atoms(AppliedUndef)
                      if a.func not in funcs and not _is_parameter_function(a.func, system.parameters)})
    if not foreign:
        return None
    states = ", ".join(s.name for s in system.states)
    return (f"{what} uses {', '.join(foreign)}, which its system does not have (the system's states: {states}); "
            f"expected a functional of the system's states; add the state to the system or use one of its states")


def _is_parameter_function(func, params) -> bool:
    return any(func in spec.symbols for spec in params)


def catalogue(*, load_limit: float | None = LOAD_LIMIT_SECONDS) -> list[ProofFile]:
    """Every proof package shipped with lkverify (``lkverify.proofs.<paper>``), in name order.

    Each is imported under its real name, so its items are the objects
    ``import lkverify.proofs.<paper>`` gives.

    Examples
    --------
    >>> import lkverify.proofs.aleksandrov2023 as paper
    >>> files = {pf.paper: pf for pf in catalogue()}
    >>> files["aleksandrov2023"].items["theorem3"] is paper.theorem3       # one object per item
    True
    >>> [pf.paper for pf in catalogue()] == sorted(files)
    True
    """
    return [load_proof_module(name, load_limit=load_limit) for name in proof_module_names()]


def proof_module_names() -> list[str]:
    """The modules of the shipped proof packages (``lkverify.proofs.<paper>``), in name order, none imported.

    >>> proof_module_names()[0]
    'lkverify.proofs.aleksandrov2017'
    """
    return [f"{PROOFS_PACKAGE}.{info.name}"
            for info in sorted(pkgutil.iter_modules(_proofs_package().__path__), key=lambda info: info.name)]


def find_items(spec: str, *, load_limit: float | None = LOAD_LIMIT_SECONDS) -> list[Item]:
    """Items named by ``spec``: ``paper.item``, ``paper`` (all its items), a path, or ``path.py::item``.

    A catalogue name is looked up in the catalogue's index (:mod:`.index`) first: an unknown one is
    refused without importing any proof, a known one imports only its paper's package.

    Raises
    ------
    InputError
        Unknown names (close names are suggested) or unloadable files.

    Examples
    --------
    >>> [item.qualified_name for item in find_items("aleksandrov2023.theorem3")]
    ['aleksandrov2023.theorem3']
    >>> find_items("aleksandrov2023.theorm3")          # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: aleksandrov2023.theorm3: unknown item; did you mean aleksandrov2023.theorem3...?
    >>> import pathlib, shutil, tempfile
    >>> d = pathlib.Path(tempfile.mkdtemp()); path = d / "mine.py"
    >>> _ = path.write_text('''"My proof."
    ... from lkverify import Parameters
    ... from lkverify.catalogue import Check
    ... PAPER = "mypaper"
    ... positive = Check("positive", parameters=Parameters(), checks=[])
    ... ''')
    >>> [item.qualified_name for item in find_items(f"{path}::positive")]
    ['mypaper.positive']
    >>> find_items(f"{path}::negative")                # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: .../mine.py::negative: no item 'negative' in .../mine.py; it has positive
    >>> shutil.rmtree(d)
    """
    path_part, _, item_part = spec.partition("::")
    if path_part.endswith(".py") or "/" in path_part or Path(path_part).is_file():
        pf = load_proof_file(path_part, load_limit=load_limit)
        if item_part:
            if item_part not in pf.items:
                raise InputError(f"{spec}: no item {item_part!r} in {path_part}; it has {', '.join(pf.items)}")
            return [pf.items[item_part]]
        return list(pf.items.values())
    package = package_of(spec)  # the index: an unknown name is refused without importing any proof
    if package is None:
        raise InputError(unknown_item_message(spec))
    found = _named(spec, [load_proof_module(package, load_limit=load_limit)])
    if found is None:  # a stale index (the item moved or was renamed): the whole catalogue decides
        files = catalogue(load_limit=load_limit)
        found = _named(spec, files)
    if found is None:
        names = [f"{pf.paper}.{n}" for pf in files for n in pf.items] + [pf.paper for pf in files]
        close = difflib.get_close_matches(spec, names, n=3, cutoff=0.5)
        hint = f"; did you mean {', '.join(close)}?" if close else "; see `lkverify list`"
        raise InputError(f"{spec}: unknown item{hint}")
    return found


def _named(spec: str, files) -> list | None:
    """The items of ``files`` that ``spec`` names (``paper.item`` or ``paper``), else None."""
    for pf in files:
        if spec == pf.paper:
            return list(pf.items.values())
        if spec.startswith(pf.paper + ".") and spec[len(pf.paper) + 1:] in pf.items:
            return [pf.items[spec[len(pf.paper) + 1:]]]
    return None
