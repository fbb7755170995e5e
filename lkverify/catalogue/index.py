"""The catalogue's index: every item's name, paper, kind and title, without importing the proofs.

``lkverify list`` prints it and an unknown name is refused from it (:func:`unknown_item_message`),
so neither imports :mod:`lkverify.proofs` or SymPy; a known name loads only its paper's package
(:func:`package_of`).  The rows are generated from the loaded catalogue into :mod:`.index_data`
(plain literals) by ``python3 -m lkverify.catalogue.index``; a test checks that the committed
index is the catalogue's (run that command after adding, renaming or retitling an item).

Examples
--------
>>> row = next(r for r in read_index() if r.item == "aleksandrov2023.theorem3")
>>> row.paper, row.kind, package_of("aleksandrov2023.theorem3")
('aleksandrov2023', 'theorem', 'lkverify.proofs.aleksandrov2023')
>>> package_of("aleksandrov2023"), package_of("aleksandrov2023.theorm3")
('lkverify.proofs.aleksandrov2023', None)
>>> unknown_item_message("aleksandrov2023.theorm3")     # doctest: +ELLIPSIS
'aleksandrov2023.theorm3: unknown item; did you mean aleksandrov2023.theorem3, ...?'
"""

from __future__ import annotations

import dataclasses
import difflib
from pathlib import Path

__all__ = ["IndexRow", "PROOFS_PACKAGE", "index_rows", "package_of", "read_index", "unknown_item_message",
           "write_index"]

#: the package holding the catalogue's proofs, one subpackage per paper
PROOFS_PACKAGE = "lkverify.proofs"

#: the generated module (next to this one)
INDEX_DATA = Path(__file__).with_name("index_data.py")

#: the command that regenerates :data:`INDEX_DATA`
REGENERATE = "python3 -m lkverify.catalogue.index"


@dataclasses.dataclass(frozen=True)
class IndexRow:
    """One catalogue item as ``lkverify list`` shows it.

    Attributes
    ----------
    item : str
        The qualified name, ``paper.name``.
    paper : str
    kind : str
        ``theorem``, ``check`` or ``example``.
    title : str
    package : str
        The proof package's name inside :data:`PROOFS_PACKAGE` (the paper's, unless the package says
        ``PAPER = …`` otherwise).

    Examples
    --------
    >>> IndexRow("mypaper.positive", "mypaper", "check", "Positivity", "mypaper").item
    'mypaper.positive'
    """

    item: str
    paper: str
    kind: str
    title: str
    package: str


def read_index() -> tuple[IndexRow, ...]:
    """The committed index, in the catalogue's order (papers by package name, items as declared).

    Examples
    --------
    >>> rows = read_index()
    >>> {r.kind for r in rows} == {"theorem", "check", "example"}
    True
    """
    from .index_data import ROWS

    return tuple(IndexRow(*row) for row in ROWS)


def package_of(name: str) -> str | None:
    """The module name of the proof package that declares ``name`` (``paper.item`` or ``paper``), else None.

    Examples
    --------
    >>> package_of("aleksandrov2017.lemma1")
    'lkverify.proofs.aleksandrov2017'
    >>> package_of("nosuchpaper.theorem1") is None
    True
    """
    for row in read_index():
        if name in (row.item, row.paper):
            return f"{PROOFS_PACKAGE}.{row.package}"
    return None


def unknown_item_message(spec: str) -> str:
    """The one-line refusal of a catalogue name that is not in the index, with close names if any.

    Examples
    --------
    >>> unknown_item_message("nothing.like.it")
    'nothing.like.it: unknown item; see `lkverify list`'
    """
    rows = read_index()
    names = [r.item for r in rows] + list(dict.fromkeys(r.paper for r in rows))
    close = difflib.get_close_matches(spec, names, n=3, cutoff=0.5)
    hint = f"; did you mean {', '.join(close)}?" if close else "; see `lkverify list`"
    return f"{spec}: unknown item{hint}"


def index_rows(files) -> tuple[IndexRow, ...]:
    """The index of loaded proof files (:class:`~lkverify.catalogue.loader.ProofFile`, as ``catalogue()`` gives).

    Examples
    --------
    >>> from lkverify.catalogue.loader import catalogue
    >>> index_rows(catalogue()) == read_index()       # the committed index is current
    True
    """
    kinds = {"Example": "example", "Check": "check"}
    rows = []
    for pf in files:
        package = pf.path.parent.name if pf.path.name == "__init__.py" else pf.path.stem
        for name, item in pf.items.items():
            rows.append(IndexRow(f"{pf.paper}.{name}", pf.paper, kinds.get(type(item).__name__, "theorem"),
                                 item.title, package))
    return tuple(rows)


def write_index(rows, path=INDEX_DATA) -> Path:
    """Write ``rows`` (:func:`index_rows` of the catalogue) as the generated module at ``path``.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "index_data.py"
    >>> _ = write_index([IndexRow("p.a", "p", "check", "A 'quoted' title", "p")], path)
    >>> namespace = {}; exec(path.read_text(encoding="utf-8"), namespace); namespace["ROWS"]
    (('p.a', 'p', 'check', "A 'quoted' title", 'p'),)
    >>> path.unlink()
    """
    lines = [f'"""The catalogue\'s index (:mod:`lkverify.catalogue.index`), generated by ``{REGENERATE}``; '
             f'do not edit."""', "", "ROWS = ("]
    lines += [f"    {dataclasses.astuple(row)!r}," for row in rows]
    lines += [")", ""]
    path = Path(path)
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def _main() -> None:
    """``python3 -m lkverify.catalogue.index``: regenerate :data:`INDEX_DATA` from the loaded catalogue."""
    from .. import catalogue as package  # the loader, through the package (the loader itself reads this index)

    rows = index_rows(package.catalogue())
    print(f"{write_index(rows)}: {len(rows)} items")


if __name__ == "__main__":  # pragma: no cover
    _main()
