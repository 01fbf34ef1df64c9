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
