"""The proof cache: decided reports of catalogue items stored on disk, keyed by what they depend on.

A catalogue item checked at given values with no wall-clock cap is deterministic: its report
(every identity proof, template supremum, LMI certificate, decay certificate and simulation
in it) is a function of lkverify's source, the proof modules' source, the values, the options
and the versions of the libraries that compute it.  The cache stores that report — its text
(plain and ``--verbose``), its JSON and its exit code — under the SHA-256 of all of these:

* the **source digest**: every ``.py`` and ``.json`` file of the installed ``lkverify`` package
  and of ``lkverify.proofs`` (path and content), so *any* change of the code makes every old
  entry unreachable (nothing is invalidated by hand, nothing stale is ever served);
* the versions of Python, lkverify and the libraries of :data:`LIBRARIES`;
* the job (``check`` or ``report``), the item's qualified name, the values (``sympy.srepr``),
  and the options that change the output (``--box``, ``--max-boxes``).

Only jobs without a wall-clock cap are stored or read (a ``--budget`` run may be cut by the
machine's load), and only catalogue items (a proof file given by path is not keyed here).

Integrity: each entry carries an HMAC-SHA256 of its payload under a random key kept in the
cache directory (file ``key``, mode 0600).  An entry that does not parse, has another key or
format, or whose HMAC does not match (a truncated write, a flipped bit, an edit) is deleted
and the report recomputed.  This detects corruption and edits by anyone who does not hold the
key; it is not a proof — the cached report is trusted as the report that was computed, not
re-derived (no certificate in it is re-checked on load).

Location: ``$LKVERIFY_CACHE_DIR`` if set, else the user cache directory of platformdirs
(``~/.cache/lkverify`` on Linux).  ``LKVERIFY_CACHE=off`` (or ``--no-cache``) bypasses it;
``lkverify cache clear`` empties it, ``lkverify cache info`` says where it is and its size.

Examples
--------
>>> import tempfile
>>> cache = ProofCache(tempfile.mkdtemp())
>>> key = cache.key("check", "demo.item", values={"k": 2})
>>> cache.get(key) is None
True
>>> cache.put(key, {"text": "demo", "exit_code": 0})
True
>>> cache.get(key)["text"], cache.stats()["entries"]
('demo', 1)
>>> key != cache.key("check", "demo.item", values={"k": 3})      # other values: another entry
True
>>> cache.clear()
1
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
import sys
import tempfile
import threading
from collections.abc import Mapping
from pathlib import Path

from .errors import InputError

__all__ = ["CACHE_FORMAT", "LIBRARIES", "CachedReport", "ProofCache", "cache_command", "cache_enabled", "cached_run",
           "default_cache", "item_key", "job_cache", "report_payload", "source_digest"]

#: the entries' format: a change makes old entries unreadable (they are recomputed)
CACHE_FORMAT = 1
#: libraries whose version is part of every key (they compute the results)
LIBRARIES = ("sympy", "numpy", "scipy", "mpmath", "python-flint", "cvxpy", "clarabel", "numba")
_ENV_DIR, _ENV_SWITCH = "LKVERIFY_CACHE_DIR", "LKVERIFY_CACHE"
_DIGEST: dict = {}
_LOCK = threading.Lock()


def source_digest() -> str:
    """SHA-256 over the path and content of every ``.py``/``.json`` file of lkverify and its proofs (once per process).

    >>> len(source_digest()), source_digest() == source_digest()
    (64, True)
    """
    with _LOCK:
        if "source" not in _DIGEST:
            import lkverify
            import lkverify.proofs

            h = hashlib.sha256()
            for root in sorted({Path(p).resolve() for p in (*lkverify.__path__, *lkverify.proofs.__path__)}):
                for path in sorted(root.rglob("*")):
                    if path.suffix in (".py", ".json") and "__pycache__" not in path.parts and path.is_file():
                        h.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes() + b"\0")
            _DIGEST["source"] = h.hexdigest()
        return _DIGEST["source"]


def _versions() -> dict:
    """Python's and the libraries' versions (once per process)."""
    with _LOCK:
        if "versions" not in _DIGEST:
            from importlib import metadata

            out = {"python": sys.version.split()[0]}
            for name in ("lkverify", *LIBRARIES):
                try:
                    out[name] = metadata.version(name)
                except metadata.PackageNotFoundError:
                    out[name] = None
            _DIGEST["versions"] = out
        return dict(_DIGEST["versions"])


def _canonical(value):
    """A JSON-able, deterministic form of a value (SymPy objects by ``srepr``)."""
    if isinstance(value, Mapping):
        return {str(k): _canonical(v) for k, v in sorted(value.items(), key=lambda kv: str(kv[0]))}
    if isinstance(value, (list, tuple)):
        return [_canonical(v) for v in value]
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return repr(value)
    import sympy

    if isinstance(value, sympy.Basic) or hasattr(value, "_sympy_"):
        return "sympy:" + sympy.srepr(sympy.sympify(value))
    return f"{type(value).__name__}:{value!r}"


def cache_enabled() -> bool:
    """False when ``LKVERIFY_CACHE`` is ``off``/``0``/``no``/``false``."""
    return os.environ.get(_ENV_SWITCH, "on").strip().lower() not in ("off", "0", "no", "false")


def default_cache() -> "ProofCache":
    """The cache at ``$LKVERIFY_CACHE_DIR`` or the user cache directory."""
    where = os.environ.get(_ENV_DIR)
    if not where:
        import platformdirs

        where = platformdirs.user_cache_dir("lkverify", appauthor=False)
    return ProofCache(where)


class ProofCache:
    """Reports on disk under content keys, each entry checked by an HMAC on read.

    Parameters
    ----------
    directory : str or Path
        Created on first write.  A directory that cannot be written makes :meth:`put` return
        False (the job goes on without a cache); it never raises for that.
    """

    def __init__(self, directory):
        if not isinstance(directory, (str, os.PathLike)) or not str(directory):
            raise InputError(f"ProofCache: expected a directory path, got {directory!r}")
        self.directory = Path(directory).expanduser()
        self._entries = self.directory / f"v{CACHE_FORMAT}"

    # -- keys --------------------------------------------------------------------------------
    def key(self, job: str, item: str, *, values: Mapping | None = None, options: Mapping | None = None) -> str:
        """The SHA-256 of the source digest, the versions, the job, the item, the values and the options."""
        blob = json.dumps({"format": CACHE_FORMAT, "source": source_digest(), "versions": _versions(), "job": job,
                           "item": item, "values": _canonical(dict(values or {})),
                           "options": _canonical(dict(options or {}))}, sort_keys=True)
        return hashlib.sha256(blob.encode()).hexdigest()

    def _path(self, key: str) -> Path:
        if len(key) != 64 or any(c not in "0123456789abcdef" for c in key):
            raise InputError(f"ProofCache: expected a key of 64 hex digits (ProofCache.key), got {key!r}")
        return self._entries / key[:2] / f"{key}.json"

    def _secret(self, create: bool) -> bytes | None:
        path = self.directory / "key"
        try:
            data = path.read_bytes()
            if len(data) == 32:
                return data
        except OSError:
            pass
        if not create:
            return None
        self.directory.mkdir(parents=True, exist_ok=True)
        data = secrets.token_bytes(32)
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        return data

    @staticmethod
    def _mac(secret: bytes, key: str, payload: str) -> str:
        return hmac.new(secret, (key + "\0" + payload).encode(), hashlib.sha256).hexdigest()

    # -- entries -----------------------------------------------------------------------------
    def get(self, key: str) -> dict | None:
        """The payload stored under ``key``, or None (absent, unreadable, or failing its HMAC: then deleted)."""
        path = self._path(key)
        try:
            raw = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            if path.exists():
                self._drop(path)
            return None
        secret = self._secret(create=False)
        try:
            entry = json.loads(raw)
            ok = (secret is not None and isinstance(entry, dict) and entry.get("key") == key
                  and isinstance(entry.get("payload"), str)
                  and hmac.compare_digest(str(entry.get("mac")), self._mac(secret, key, entry["payload"])))
            payload = json.loads(entry["payload"]) if ok else None
        except (ValueError, TypeError, KeyError):
            ok, payload = False, None
        if not ok or not isinstance(payload, dict):
            self._drop(path)
            return None
        return payload

    def put(self, key: str, payload: Mapping) -> bool:
        """Store ``payload`` (JSON-able) under ``key``, atomically; False when the directory cannot be written."""
        path = self._path(key)
        text = json.dumps(dict(payload), ensure_ascii=False)
        try:
            secret = self._secret(create=True)
            path.parent.mkdir(parents=True, exist_ok=True)
            entry = json.dumps({"key": key, "payload": text, "mac": self._mac(secret, key, text)}, ensure_ascii=False)
            fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                fh.write(entry)
            os.replace(tmp, path)
        except OSError:
            return False
        return True

    @staticmethod
    def _drop(path: Path) -> None:
        try:
            path.unlink()
        except OSError:
            pass

    def clear(self) -> int:
        """Delete every entry (and the key); the number of entries deleted."""
        n = 0
        if self._entries.is_dir():
            for path in self._entries.rglob("*.json"):
                self._drop(path)
                n += not path.name.startswith(".tmp-")
        self._drop(self.directory / "key")
        return n

    def stats(self) -> dict:
        """{"directory", "entries", "bytes"} of the cache."""
        files = [p for p in self._entries.rglob("*.json") if not p.name.startswith(".tmp-")] \
            if self._entries.is_dir() else []
        return {"directory": str(self.directory), "entries": len(files),
                "bytes": sum(p.stat().st_size for p in files)}


def report_payload(report) -> dict:
    """What the cache stores of a :class:`~lkverify.report.results.Report`: its texts, JSON and exit code.

    >>> from lkverify.report.results import Report, Result
    >>> from lkverify.status import Status
    >>> p = report_payload(Report("demo", {}, (Result("bound", "m", Status.CERTIFIED, 0.25, "m > 0"),), "holds"))
    >>> sorted(p), p["exit_code"], CachedReport(p).as_text() == p["text"]
    (['exit_code', 'holds', 'json', 'text', 'text_verbose'], 0, True)
    """
    return {"text": report.as_text(verbose=False), "text_verbose": report.as_text(verbose=True),
            "json": report.to_json(), "holds": bool(report.holds), "exit_code": int(report.exit_code)}


class CachedReport:
    """A report read from the cache: the interface the command line prints from (text, JSON, exit code)."""

    def __init__(self, payload: Mapping):
        missing = [k for k in ("text", "text_verbose", "json", "holds", "exit_code") if k not in payload]
        if missing:
            raise InputError(f"CachedReport: expected a payload of report_payload, missing {', '.join(missing)}")
        self._payload = dict(payload)
        self.item = self._payload["json"].get("item")
        self.holds = bool(self._payload["holds"])
        self.exit_code = int(self._payload["exit_code"])

    def as_text(self, verbose: bool = False) -> str:
        return self._payload["text_verbose" if verbose else "text"]

    def to_json(self) -> dict:
        return json.loads(json.dumps(self._payload["json"]))


def job_cache(no_cache: bool = False) -> "ProofCache | None":
    """The cache a command-line job uses: None with ``--no-cache`` or ``LKVERIFY_CACHE=off``."""
    return None if no_cache or not cache_enabled() else default_cache()


def item_key(cache: "ProofCache | None", item: str, values: Mapping | None = None, *, boxes=(),
             max_boxes: int | None = None) -> str | None:
    """The key of ``check ITEM`` (the bare report's items are ``check ITEM`` at no values), None without a cache."""
    if cache is None:
        return None
    return cache.key("check", item, values=values, options={"box": list(boxes), "max_boxes": max_boxes})


def cached_run(cache: "ProofCache | None", key: str | None, run, *, note=None):
    """``run()`` (a report), or the report stored under ``key``; a computed report is stored.

    ``note(message)`` is told when the report comes from the cache.

    >>> import tempfile
    >>> from lkverify.report.results import Report
    >>> cache = ProofCache(tempfile.mkdtemp()); key = item_key(cache, "demo.item")
    >>> calls = []
    >>> def run():
    ...     calls.append(1)
    ...     return Report("demo.item", {}, (), "every check holds")
    >>> a = cached_run(cache, key, run); b = cached_run(cache, key, run)
    >>> len(calls), type(b).__name__, a.as_text() == b.as_text()
    (1, 'CachedReport', True)
    """
    hit = cache.get(key) if cache is not None and key is not None else None
    if hit is not None:
        report = CachedReport(hit)
        if note:
            note(f"{report.item}: from the proof cache ({cache.directory}; --no-cache recomputes)")
        return report
    report = run()
    if cache is not None and key is not None:
        cache.put(key, report_payload(report))
    return report


def cache_command(action: str, *, json_out: bool = False) -> int:
    """``lkverify cache info`` / ``lkverify cache clear``: print, return the exit code."""
    cache = default_cache()
    if action == "clear":
        n = cache.clear()
        print(json.dumps({"directory": str(cache.directory), "deleted": n}) if json_out else
              f"{n} entries deleted from {cache.directory}")
        return 0
    if action == "info":
        st = cache.stats()
        st["enabled"] = cache_enabled()
        print(json.dumps(st) if json_out else
              f"proof cache: {st['directory']}\n  {st['entries']} entries, {st['bytes'] / 1e6:.2f} MB"
              + ("" if st["enabled"] else f"\n  disabled ({_ENV_SWITCH}={os.environ.get(_ENV_SWITCH)})"))
        return 0
    raise InputError(f"cache: expected info or clear, got {action!r}; e.g. lkverify cache clear")
