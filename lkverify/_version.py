"""The version of lkverify: the installed distribution's (pyproject.toml is the one source)."""

__all__ = ["__version__"]


def _package_version() -> str:
    """The installed distribution's version (pyproject.toml is the one source)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("lkverify")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
        return "0+unknown"


__version__ = _package_version()
