"""Type information of the extension module ``wbv._wbv`` (re-exported by ``wbv``).

Units are SI throughout: accelerations in m/s², forces in N, rates and frequencies in Hz, times and
durations in s, masses in kg. Channel names follow the measured-run convention
(docs/measured-runs.md): ``a_<place>_<axis>`` for accelerations (``a_base_z``, ``a_seat_z``,
``a_seat_x``, ``a_head_z``, ``a_back_x``, …) and ``f_<place>_<axis>`` for forces (``f_seat_z``).
"""

import os
import pathlib
from collections.abc import Mapping, Sequence
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str
"""The version of wbv the module was built from."""

ArrayLike = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]
Document = dict[str, Any]

class WbvError(ValueError):
    """Bad input or a failed computation. ``str(error)`` is the message ``wbv`` prints after
    ``wbv: error:``, the parameter named by its Python keyword (``fs: -5 Hz; expected a positive
    sample rate``, ``operations[0]: -1 h; …``), a file or line, and what was expected; a sample
    by its 0-based index as numpy counts (``sample 100 (index 99) is not finite``). A value of the
    wrong type (``fs="1000"``) raises ``TypeError: fs must be a number (got str)`` instead, and
    complex samples are refused."""

def analyze(
    channels: Mapping[str, ArrayLike],
    fs: float,
    *,
    units: Union[None, str, Mapping[str, str]] = None,
    exposure_hours: Optional[float] = 8.0,
    resolution_hz: float = 0.125,
) -> Document:
    """ISO 2631-1:1997 analysis of sampled channels: the document ``wbv analyze --json
    --exposure-hours 8`` prints for the same samples (``--resolution``, ``--units`` alike).

    Parameters
    ----------
    channels
        ``{name: samples}``, e.g. ``{"a_base_z": base, "a_seat_z": seat}``: 1-D arrays of equal
        length, at least 10 s long. Accelerations in m/s² and forces in N unless ``units`` says
        otherwise. Any other name, a non-finite sample or one beyond 10⁴ m/s² (10⁶ N) raises
        :class:`WbvError`.
    fs
        Sample rate in Hz (> 0; 160 Hz and up for the weightings up to 80 Hz).
    units
        Unit of the samples: one for every channel (``"g"``, ``"mg"``, ``"m/s2"``, ``"N"``,
        ``"kN"``) or ``{channel: unit}``. Without it the samples are read as m/s² (N), and a
        channel that looks like g is flagged in ``warnings`` and its verdicts marked doubtful.
    exposure_hours
        Daily exposure in h for the health assessment (ISO 2631-1 clause 7 and Annex B, Directive
        2002/44/EC); ``None`` leaves ``health`` out.
    resolution_hz
        Resolution of the Welch PSD behind the one-third-octave bands, Hz.

    Returns
    -------
    dict
        The JSON document: ``channels`` (per channel ``a_w`` and ``rms`` in m/s², ``vdv`` in
        m/s^1.75, ``mtvv`` in m/s², ``crest_factor``, ``msdv`` in m/s^1.5, weighting and ``k``),
        ``total_value`` a_v in m/s² (eq. 10), ``comfort`` (Annex C class), ``seat_percent``
        (ISO 10326-1 SEAT, %), ``health`` (A(8) in m/s², VDV, zone), ``weighted_bands``
        (one-third-octave band r.m.s. in m/s² per channel), ``units`` (the unit of every key),
        ``warnings`` (what the reader decided, each ``input: …``) and ``command``.
    """

class Run:
    """A simulated run (:func:`simulate`)."""

    channels: dict[str, np.ndarray]
    """Measured channels: ``a_base_z``, ``a_seat_z``, ``a_head_z`` (and ``a_seat_x``, … for models
    with fore-and-aft motion) in m/s², ``f_seat_z`` (and ``f_back_z``) in N; equal to the columns
    ``wbv simulate --csv`` writes."""
    time: np.ndarray
    """Time of every sample in s (the CSV's ``t_s``), from 0."""
    fs: float
    """Sample rate in Hz (1/dt)."""
    figures: Optional[Document]
    """The ISO 2631-1 report of the channels (the document's ``analysis``, the same keys as
    :func:`analyze` returns); ``None`` when the sample rate allows none."""
    document: Document
    """The document of ``wbv simulate --json``: model, excitation, integrator, ``dt_s``,
    ``duration_s``, ``seed``, ``elapsed_s``, ``written`` (files), ``analysis``."""
    path: Optional[pathlib.Path]
    """The recording ``<record>/run.mcap``, when ``record`` named a directory."""

def simulate(
    model: str,
    excitation: str,
    duration: float,
    seed: int,
    *,
    dt: float = 0.001,
    integrator: str = "newmark",
    record: Optional[PathLike] = None,
    force: bool = False,
    **options: Any,
) -> Run:
    """Simulates ``model`` shaken at its base by ``excitation`` (time domain), as ``wbv simulate``.

    Parameters
    ----------
    model
        A built-in model (:func:`models`), a model TOML file, or components joined by ``+``
        (``"wan-schimmels-4dof+cushion-zener"``).
    excitation
        A built-in excitation (:func:`excitations`), a TOML file, or one of ``random``, ``psd``,
        ``road``, ``recorded``, ``sine``, ``sweep`` built from ``options``.
    duration
        Simulated time in s (> 0).
    seed
        Seed of the random excitation (0 … 2⁶⁴ − 1); the same seed gives the same samples.
    dt
        Time step in s.
    integrator
        ``"newmark"`` (average acceleration), ``"newmark-linear"`` or ``"rk4"``.
    record
        A run directory: the run is recorded to ``<record>/run.mcap`` (with the viewer files beside
        it), refused if it exists unless ``force``. Without it nothing is written.
    options
        The excitation's options, as ``wbv simulate``'s: ``rms`` (m/s², random), ``band`` ((F1, F2)
        Hz, random), ``freq`` (Hz, sine), ``amplitude`` (m/s² peak, sine and sweep), ``fade_in``
        (s), ``sweep`` ((F0, F1) Hz), ``sweep_law`` (``"log"``/``"linear"``), ``sweep_duration``
        (s), ``input`` (a file, recorded and psd), ``road_class`` (``"A"`` … ``"H"``), ``speed``
        (m/s, road), and for ``recorded`` ``units``, ``fs``, ``columns``, ``topic``. An option the
        excitation does not use raises :class:`WbvError`.

    Ctrl-C stops the run within a step and raises ``KeyboardInterrupt``; a recording in progress
    is removed.
    """

def models() -> list[Document]:
    """The built-in models (``wbv models --json``'s ``models``): ``name``, ``kind``, ``dof``
    (degrees of freedom), ``description``, ``params`` (parameter paths for :func:`sweep`)."""

def excitations() -> list[Document]:
    """The built-in excitations (``wbv excitations --json``'s ``excitations``): ``name``,
    ``description``, ``origin``, ``rms_m_s2`` (steady-state r.m.s. in m/s², ``None`` for a
    recording)."""

class Frf:
    """A model's frequency responses (:func:`frf`)."""

    model: str
    freq_hz: np.ndarray
    """The frequencies in Hz."""
    responses: dict[str, np.ndarray]
    """Complex response per name, per unit base acceleration (paper 001 eqs. 8–10, paper 002):
    ``stht`` (seat-to-head transmissibility, 1), ``seat`` (seat transmissibility, 1), ``apms``
    (apparent mass, kg), ``dpmi`` (driving-point mechanical impedance, N·s/m), ``t_<mass>``
    (base-to-mass transmissibility, 1); planar models also ``seat_x``, ``head_z``, ``head_x``,
    ``apms_z``, ``apms_x``."""
    units: dict[str, str]
    """Unit of each response's magnitude: ``"1"``, ``"kg"`` or ``"N·s/m"``."""

def frf(model: str, freqs: ArrayLike, *, foam_thickness: Optional[float] = None) -> Frf:
    """The linearised frequency responses of ``model`` at ``freqs`` Hz (finite, ≥ 0), as
    ``wbv frf`` computes them; ``foam_thickness`` in m for planar models (paper 000: 0.06, 0.08,
    0.10)."""

def modes(model: str, *, foam_thickness: Optional[float] = None) -> Document:
    """The document of ``wbv modes --json``: ``undamped`` (``freq_hz``, ``shape`` over ``masses``,
    largest = 1), ``damped`` (state-space eigenvalues: ``damped_hz``, ``natural_hz``, ``zeta``,
    ``overdamped``, ``shape_mag``, ``shape_phase_deg``), and where the model has them
    ``equilibrium`` (loads in N, points in m, moments in N·m) and ``described`` (motions in words
    with the vertical and fore-and-aft effective mass fractions)."""

def sweep(
    model: str,
    params: Mapping[str, Union[str, Sequence[float], ArrayLike]],
    *,
    response: str = "stht",
    from_hz: float = 0.5,
    to_hz: float = 20.0,
    points: int = 400,
    excitation: Optional[str] = None,
    duration: float = 60.0,
    dt: float = 0.001,
    seed: int = 1,
    integrator: str = "newmark",
    time_domain: bool = False,
    **options: Any,
) -> Any:
    """A parameter sweep, as ``wbv sweep --json``: one row per grid point.

    ``params`` maps a parameter path (:func:`models` ``params``, e.g. ``"link.cushion.k"`` in N/m,
    ``"link.cushion.zeta@60"``) to its values, an array or the command's ``"from:to:count"``; two
    parameters make a grid (the first varying slowest). The response (``stht``, ``seat``, ``apms``,
    ``dpmi``, ``t_<mass>``) is evaluated on ``points`` frequencies from ``from_hz`` to ``to_hz``.
    With an ``excitation`` (and its ``options``, as for :func:`simulate`), every point also gets
    its ISO 2631-1 figures: from the spectrum for a linear model under a stationary excitation,
    else (or with ``time_domain``) simulated for ``duration`` s with the same ``seed`` at every
    point.

    Returns a pandas DataFrame when pandas is installed (the document's other keys, such as
    ``path`` — how the figures were computed and why — in ``DataFrame.attrs``), else a dict of
    numpy arrays. Columns: ``point``, each parameter, ``peak_freq_hz`` (Hz), ``peak_mag`` (the
    response's unit), and with an excitation ``a_w_seat_m_s2``, ``a_v_m_s2``, ``seat_pct``,
    ``comfort`` (Annex C class) and on the time-domain path ``vdv_seat_m_s1_75``,
    ``mtvv_seat_m_s2``, ``crest_seat``.
    """

def seat_test(
    model: Optional[str] = None,
    classes: Union[None, str, Sequence[str]] = None,
    *,
    runs: Optional[Sequence[Union[Mapping[str, ArrayLike], PathLike]]] = None,
    occupant: Optional[str] = None,
    seat_limit: Optional[float] = None,
    damping_limit: Optional[float] = None,
    contact_limit: Optional[float] = None,
    duration: float = 600.0,
    dt: float = 0.001,
    seed: int = 1,
    damping: bool = True,
    fs: Optional[float] = None,
    units: Union[None, str, Mapping[str, str]] = None,
) -> Document:
    """The ISO 10326-1 laboratory seat test (docs/seat-test.md): the document of ``wbv seat-test
    --json``.

    Simulated: ``model`` (a chain of masses with a seat, e.g. ``"scissor-seat"``) on each input
    spectral class of ``classes`` (a name, a comma-separated list or a list: ``"iso7096-em1"`` …
    ``"em9"``, ``"en13490-it1"`` … ``"it4"``, ``"iso5007-ag1"`` … ``"ag3"``; :func:`excitations`),
    for the light (53.5 kg) and heavy (100.5 kg) test person or the one ``occupant`` names
    (``"light"``, ``"heavy"``): runs of ``duration`` s (600 s each; the standard's duration not
    read) at step ``dt`` s, run i with seed ``seed + i``, until three consecutive runs agree within
    ±5 % in a_wP (clause 10.2.1); then the damping test (clause 10.3), once, unless ``damping`` is
    false. Three classes with the defaults: about 30 s of wall time on two cores (measured 32 s).

    Measured: ``model=None`` and ``runs``, three or more runs in the order made, each
    ``{channel: samples}`` at ``fs`` Hz with platform ``a_base_z`` and seat ``a_seat_z`` (m/s²
    unless ``units`` says otherwise) or a file ``wbv seat-test --run`` reads; one class. A run given
    twice is a warning.

    ``seat_limit`` (SEAT, ratio), ``damping_limit`` (transmissibility) and ``contact_limit``
    (end-stop contacts per 10 min of run, each test person) are the application standard's;
    without a contact limit, end-stop impacts make the verdict ``"warning"``. Returns ``summary``
    (one row per class and test person: ``seat``, ``a_ws_corrected`` m/s², ``end_stop_contacts``,
    ``contacts_per_10_min``, ``damping_transmissibility``, ``verdict``), ``verdict``
    (``"pass"``, ``"warning"``, ``"fail"`` or ``None``), ``verdict_lines``, ``damping``
    (``f_r_hz`` Hz, ``transmissibility``), ``classes`` (per class: ``a_wp``, ``a_ws``,
    ``a_ws_corrected``, ``intended_a_wp`` m/s² Wk-weighted, ``seat`` (a_wS/a_wP, clause 10.2.2),
    ``occupants`` with their ``runs``, ``impacts`` (``peak_seat_acceleration_m_s2``,
    ``vdv_added_m_s1_75``) and ``seat_resonance_hz``, ``machine``, ``defining``, ``scope``,
    ``verdict_line``, ``notes``, ``unverified``), ``warnings`` and ``units``.
    """

def exposure(
    operations: Sequence[
        Union[
            tuple[Union[Mapping[str, ArrayLike], PathLike], float],
            tuple[str, Union[Mapping[str, ArrayLike], PathLike], float],
            tuple[Mapping[str, ArrayLike], float, float],
            tuple[str, Mapping[str, ArrayLike], float, float],
            Any,  # wbv.Operation(channels, fs, hours, name=None)
        ]
    ],
    *,
    fs: Optional[float] = None,
    units: Union[None, str, Mapping[str, str]] = None,
    iso2631_5: bool = False,
    spine_sex: str = "male",
    spine_start_age: Optional[float] = None,
    spine_years: Optional[int] = None,
    spine_days_per_year: Optional[float] = None,
) -> Document:
    """A working day of several operations (docs/exposure.md): the document of ``wbv exposure
    --json``.

    Each operation is ``(samples, hours)`` or ``(name, samples, hours)`` with ``samples`` a
    ``{channel: samples}`` mapping at ``fs`` Hz or a file ``wbv exposure --operation FILE:HOURS``
    reads (named by its path); ``(samples, fs, hours)`` or ``(name, samples, fs, hours)`` for
    arrays with their own rate (Hz), or ``wbv.Operation(channels, fs, hours, name=None)``. Arrays from loggers at different rates
    need their own: one ``fs`` for a 500 Hz and a 2048 Hz array reads one at the other's rate, as
    another duration and another A(8). ``hours`` is its hours a day (0 < h ≤ 24, at most 24 in
    all); a record lasting more than 1.1 × its hours is a warning (its rate or its hours are
    wrong). Returns the day's ``a8`` (A(8), m/s², ISO 2631-1 Annex B and Directive 2002/44/EC,
    worst axis with k = 1.4, 1.4, 1), ``vdv_day`` (m/s^1.75), ``zone`` (``below_action``,
    ``above_action``, ``above_limit``), the hours to each action and limit value (h, ``None`` when
    a day never reaches it), ``operations`` (per operation k·a_w, k·VDV and its share of the day),
    ``axes``, ``warnings``, and with ``iso2631_5`` (or a seat crest factor above 9) the ISO
    2631-5:2018 block ``iso2631_5`` (D_z, S_ed in MPa, R) for the exposure history ``spine_*``
    (Annex C; unset: its worked example, a man from 20 years of age for 20 years, 120 days a
    year).
    """

def gap(
    runs: Sequence[Union[Mapping[str, ArrayLike], PathLike]],
    check: Union[Mapping[str, ArrayLike], PathLike],
    model: str,
    *,
    fs: Optional[float] = None,
    loggers: Optional[Sequence[str]] = None,
    units: Union[None, str, Mapping[str, str]] = None,
) -> Document:
    """The sim-to-real gap diagnosis of ``model`` (docs/gap.md): the document of ``wbv gap
    --json``.

    ``runs`` are the training runs (at different magnitudes) and ``check`` the held-out run, each
    ``{channel: samples}`` at ``fs`` Hz (at least ``a_base_z`` and ``a_seat_z``; ``a_head_z``,
    ``f_seat_z``, ``f_back_z``, fore-and-aft channels add paths) or a file ``wbv gap`` reads.
    ``loggers`` as the command's ``--logger`` (``"cab:a_seat_z,a_head_z"``). Returns ``verdict``,
    ``named`` effects, ``warnings`` and everything the command prints.
    """
