"""Results and reports: what every job returns, prints and serialises (the JSON card of DESIGN.md)."""

from .files import check_writable_file
from .results import Kind, Report, Result, jsonable

__all__ = ["Kind", "Report", "Result", "check_writable_file", "jsonable"]
