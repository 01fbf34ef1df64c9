"""wbv from Python: whole-body-vibration simulation of seated occupants and ISO 2631-1 analysis,
numpy arrays in and numpy arrays out (docs/python.md).

Every function is the library behind the ``wbv`` command: ``wbv.analyze`` returns the document
``wbv analyze --json`` prints for the same samples, ``wbv.simulate`` the channels ``wbv simulate
--csv`` writes. Bad input raises :class:`WbvError` (a :class:`ValueError`) with the command's
message. Units are SI: samples in m/s² (accelerations ``a_*``) and N (forces ``f_*``), rates and
frequencies in Hz, durations in s.
"""

from ._wbv import (
    Frf,
    Run,
    WbvError,
    __version__,
    analyze,
    excitations,
    exposure,
    frf,
    gap,
    models,
    modes,
    seat_test,
    simulate,
    sweep,
)

__all__ = [
    "Frf",
    "Run",
    "WbvError",
    "__version__",
    "analyze",
    "excitations",
    "exposure",
    "frf",
    "gap",
    "models",
    "modes",
    "seat_test",
    "simulate",
    "sweep",
]


from dataclasses import dataclass as _dataclass
from typing import Any as _Any, Mapping as _Mapping, Optional as _Optional


@_dataclass(frozen=True)
class Operation:
    """One operation of a working day for :func:`exposure`: ``channels`` (``{name: samples}``,
    m/s² unless ``exposure(units=…)`` says otherwise) sampled at ``fs`` Hz, done ``hours`` hours a
    day (0 < h ≤ 24), named ``name`` in the document (``operations[i]`` when None)."""

    channels: _Mapping[str, _Any]
    fs: float
    hours: float
    name: _Optional[str] = None


__all__.append("Operation")
