"""slipload: choose friction-damper slip loads for buildings — the engine in Python.

The same engine as the ``slipload`` command line, not a wrapper around it: scenes,
buildings and studies load through the same validation, simulations run the same
integrators, studies run the same journalled pipeline and write the same files.

Units are SI throughout: metres, seconds, newtons, kilograms; accelerations in m/s²
unless a name says ``_g``. Per-storey results are numpy arrays indexed from the first
storey (index 0 = storey 1).

Records
    :func:`read_record`, :func:`record_from_array`, :func:`synthetic_suite`, :class:`Record`
    (``.spectrum()``, ``.intensity()``).
One simulation
    :func:`load_scene`, :func:`simulate` → :class:`Result` (peaks, residuals, slips,
    energies, transitions, ductility, collapse; ``.history`` when asked).
Many simulations
    :func:`batch` (a list of scenes), :func:`batch_designs` (one building × records ×
    slip-load vectors → arrays shaped (designs, records, storeys)).
Studies
    :func:`load_study`, :func:`optimize`, :func:`sweep`, :func:`merge`, :func:`rank`,
    :func:`table`.

Errors are :class:`InputError` (a ``ValueError``: a file, field or argument is wrong, with
the message the command line prints), :class:`FileError` (an ``OSError``),
:class:`SimulationError` and :class:`InternalError` (``RuntimeError``); all are
:class:`SlipLoadError`. Long calls release the GIL, report progress and stop on Ctrl-C
with ``KeyboardInterrupt``.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from . import _slipload
from ._errors import FileError, InputError, InternalError, SimulationError, SlipLoadError
from ._slipload import History, Record, Result, Scene, Study

__version__: str = _slipload.__version__
"""The slipload version (the workspace's)."""

NUMERICS_VERSION: int = _slipload.NUMERICS_VERSION
"""Version of the integrators' numerics (part of every study's fingerprint)."""

PathLike = Union[str, "os.PathLike[str]"]
Progress = Union[None, bool, Callable[[str, int, int], Any]]

__all__ = [
    "__version__",
    "NUMERICS_VERSION",
    "SlipLoadError",
    "InputError",
    "FileError",
    "SimulationError",
    "InternalError",
    "Record",
    "Scene",
    "Result",
    "History",
    "Study",
    "StudyReport",
    "read_record",
    "record_from_array",
    "synthetic_suite",
    "load_scene",
    "simulate",
    "batch",
    "batch_designs",
    "load_study",
    "optimize",
    "sweep",
    "merge",
    "rank",
    "table",
    "evaluate_objectives",
    "nondominated_ranks",
    "hypervolume",
    "knee",
    "allow_large",
]


# ----------------------------------------------------------------------------- progress


class _Bars:
    """Progress as tqdm bars, one per phase of a call."""

    def __init__(self) -> None:
        from tqdm.auto import tqdm  # noqa: F401  (checked by the caller)

        self._tqdm = tqdm
        self._bar = None
        self._phase = None

    def __call__(self, phase: str, done: int, total: int) -> None:
        if phase != self._phase:
            self.close()
            self._phase = phase
            self._bar = self._tqdm(total=total or None, desc=phase, leave=False)
        if self._bar is not None:
            self._bar.n = done
            self._bar.refresh()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None


def _progress(progress: Progress) -> Tuple[Optional[Callable[[str, int, int], Any]], Optional[_Bars]]:
    """The callback for ``progress``: a callable as given; ``True`` a tqdm bar; ``None`` a
    tqdm bar when tqdm is installed, else nothing; ``False`` nothing."""
    if progress is False:
        return None, None
    if callable(progress):
        return progress, None
    if progress is not None and progress is not True:
        raise InputError(
            f"progress: expected a callable progress(phase, done, total), True, False or None, got {progress!r}"
        )
    try:
        bars = _Bars()
    except ImportError:
        if progress is True:
            raise InputError("progress=True draws a tqdm bar: pip install tqdm") from None
        return None, None
    return bars, bars


def _watched(call: Callable[..., Any], progress: Progress, *args: Any, **kwargs: Any) -> Any:
    callback, bars = _progress(progress)
    try:
        return call(*args, progress=callback, **kwargs)
    finally:
        if bars is not None:
            bars.close()


# ------------------------------------------------------------------------------ records


def read_record(path: PathLike, units: Optional[str] = None, dt: Optional[float] = None) -> Record:
    """Reads a ground-motion record file: a PEER ``.AT2`` file (values in g) or a CSV/text
    file (one column of accelerations with ``dt``, or time and acceleration columns;
    values in the unit the column header states — ``accel_g``, ``a (cm/s2)`` — else in
    m/s², unless ``units`` says otherwise).

    Args:
        path: the file.
        units: units of the values: ``"g"``, ``"m/s2"``, ``"cm/s2"`` (default: the unit
            the file states, else the format's — g for AT2, m/s² for text). A CSV header
            that states another unit is refused; for an AT2 file whose title states
            another unit, ``units`` wins and a warning (and ``Record.notes``) says so.
        dt: time step of a one-column text file, s (for an AT2 file or a time column it
            must agree with the file's step).

    Returns:
        The record, its accelerations held in m/s².

    Raises:
        InputError: the file is not a record (the message names the line and what was
            expected), or ``units`` contradict its header. FileError: the file cannot be
            read.
    """
    record = Record.read(os.fspath(path), units=units, dt=dt)
    for note in record.notes:
        warnings.warn(note, UserWarning, stacklevel=2)
    return record


def record_from_array(accel: Any, dt: float, units: str = "m/s2", name: str = "array") -> Record:
    """A record from a numpy array of ground accelerations at a uniform step.

    Args:
        accel: 1-D float64 numpy array, contiguous, every value finite (an int array
            or a strided view is refused, not silently converted).
        dt: time step, s (> 0).
        units: units of ``accel``: ``"m/s2"`` (default), ``"g"`` or ``"cm/s2"``.
        name: the record's name in results and errors.

    Raises:
        InputError: an empty, non-finite, int or non-contiguous array, a bad step or unit,
            or accelerations no ground has produced.
    """
    return Record.from_array(accel, dt, units=units, name=name)


def synthetic_suite(
    count: Optional[int] = None,
    seed: Optional[int] = None,
    pga_g: Optional[float] = None,
    duration: Optional[float] = None,
    dt: Optional[float] = None,
) -> List[Record]:
    """Synthetic (Clough–Penzien filtered, enveloped) ground motions.

    With no arguments: the embedded suite the command line and the benchmark study use —
    10 records, seed 2007, 20 s at dt = 0.01 s, each scaled to PGA 0.4 g.

    Args:
        count: number of records (default 10).
        seed: the suite's seed (default 2007); record i is drawn from a seed derived
            from it and i.
        pga_g: peak ground acceleration each record is scaled to, g (default 0.4).
        duration: duration of each record, s (default 20).
        dt: time step, s (default 0.01).
    """
    return _slipload.synthetic_suite(count=count, seed=seed, pga_g=pga_g, duration=duration, dt=dt)


# ------------------------------------------------------------------------------- scenes


def _json_text(value: Any, name: str, what: str) -> str:
    """``value`` (a dict or list given for a ``what`` file) as the JSON text the loaders
    read, refused as the command line refuses the same file: larger than
    ``MAX_CONFIG_BYTES`` of text, nested deeper than the JSON reader goes, or holding NaN,
    ±inf or a value no JSON file holds; numpy numbers and arrays are taken as the numbers
    and lists they show. Every refusal is an :class:`InputError` naming ``name`` and the
    field path (``dissipators[0].slip_load``)."""
    return _slipload.dict_json(value, name, what)


def _warn(results: Iterable[Result], stacklevel: int = 3) -> None:
    """The plausibility warnings of ``results`` (``Result.warnings``: a slip load that
    looks like kN written as N, a step past the duration), as ``UserWarning``\ s in the
    words ``slipload simulate`` prints after "warning: "."""
    seen = set()
    for r in results:
        for text in r.warnings:
            if text not in seen:
                seen.add(text)
                warnings.warn(text, UserWarning, stacklevel=stacklevel)


def load_scene(
    scene: Union[None, PathLike, Dict[str, Any], Scene] = None,
    *,
    record: Union[None, Record, PathLike] = None,
    units: Optional[str] = None,
    scale_pga_g: Optional[float] = None,
    scale: Optional[float] = None,
    window: Optional[Tuple[float, float]] = None,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
) -> Scene:
    """A scene: a building under a ground motion, a method and its outputs.

    Args:
        scene: a scene or building file (JSON), a dict with a scene's or building's
            fields (relative paths resolve from the current folder; held to a file's
            rules — at most ``MAX_CONFIG_BYTES`` as JSON, nested at most 128 deep, every
            number finite — with numpy numbers and arrays taken as the numbers they
            show; an error names the field path), an existing
            :class:`Scene` (re-resolved with the overrides), or ``None`` for the embedded
            benchmark building under the first record of the embedded synthetic suite.
        record: a :class:`Record` or a record file, replacing the scene's ground motion.
        units: units of that record file's values (``"g"``, ``"m/s2"``, ``"cm/s2"``).
        scale_pga_g: scale the ground motion to this PGA, g.
        scale: multiply the ground motion by this factor (a suite's scale factor; in place
            of the scene's own ``scale`` or ``scale_pga_g``; not with ``scale_pga_g``).
        window: ``(start, duration)`` of the ground motion to use, s.
        method: ``"newmark"`` (default), ``"hht"``, ``"bilinear"``, ``"delacruz"`` or
            ``"exact"``.
        dt: time step, s (default T1/400, delacruz T1/200, rounded to divide the record's
            step).
        duration: simulated time, s (default: the window's, else the record's).

    Raises:
        InputError: a bad file or field, with the message the command line prints.
    """
    kw = dict(record=record, units=units, scale_pga_g=scale_pga_g, scale=scale, window=window, method=method, dt=dt, duration=duration)
    if isinstance(record, os.PathLike):
        kw["record"] = os.fspath(record)
    if scene is None:
        return Scene.benchmark(**kw)
    if isinstance(scene, Scene):
        return scene.replace(**kw)
    if isinstance(scene, dict):
        return Scene.from_json(_json_text(scene, "scene (a dict)", "scene"), "scene (a dict)", **kw)
    if isinstance(scene, (str, os.PathLike)):
        return Scene.load(os.fspath(scene), **kw)
    raise InputError(f"scene: expected a file path, a dict, a slipload.Scene or None, got a {type(scene).__name__}")


def _scene(scene: Union[None, PathLike, Dict[str, Any], Scene]) -> Scene:
    return scene if isinstance(scene, Scene) else load_scene(scene)


def simulate(
    scene: Union[None, PathLike, Dict[str, Any], Scene] = None,
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
    outputs: Optional[Iterable[str]] = None,
) -> Result:
    """Runs one simulation, as ``slipload simulate`` does.

    Args:
        scene: a :class:`Scene`, a scene or building file, a dict, or ``None`` for the
            embedded default scene (see :func:`load_scene`); a scene in plan's file runs
            as ``slipload simulate`` runs it (``Result.to_json()`` names its drifts,
            points and dampers under ``in_plan``).
        method: integration method for this run (default: the scene's; ``"newmark"``
            unless the scene says otherwise).
        dt: time step for this run, s (default: the scene's).
        duration: simulated time for this run, s (default: the scene's).
        outputs: what to compute besides the peaks: any of ``"histories"`` (time
            histories, see :class:`History`) and ``"energies"`` (the energy balance).
            ``None`` keeps the scene's outputs (energies on, histories off); a list
            computes exactly what it names — unasked outputs cost nothing.

    Returns:
        A :class:`Result`: per-storey numpy arrays in SI units (``peak_drift`` m,
        ``peak_drift_ratio``, ``peak_abs_acceleration`` m/s², ``residual_drift`` m,
        ``peak_slip`` m, ``transitions``), ``peak_base_shear`` N, ``energy`` (J),
        ``peak_ductility``, ``collapse``, and ``history`` when asked.

    Raises:
        InputError: bad scene or argument. SimulationError: the run failed (a response
            that is not finite, a solver that did not converge).

    Warns:
        UserWarning: what ``slipload simulate`` warns about, in its words (also in
        ``Result.warnings``): a slip load below 0.1 % of its floor's weight ("did you
        mean kN?"), a time step that does not divide the duration.
    """
    if isinstance(scene, (str, os.PathLike)) and _slipload.is_in_plan(os.fspath(scene)):
        # a scene in plan: the command line's run of it, the same Result
        return _slipload.simulate_in_plan(
            os.fspath(scene), method=method, dt=dt, duration=duration, outputs=_outputs(outputs)
        )
    result = _slipload.simulate(_scene(scene), method=method, dt=dt, duration=duration, outputs=_outputs(outputs))
    _warn([result])
    return result


def _outputs(outputs: Optional[Iterable[str]]) -> Optional[List[str]]:
    if outputs is None:
        return None
    if isinstance(outputs, str):
        return [outputs]
    return list(outputs)


def batch(
    scenes: Sequence[Union[Scene, PathLike, Dict[str, Any]]],
    *,
    outputs: Optional[Iterable[str]] = None,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> List[Result]:
    """Runs every scene of a list in parallel (rayon, the GIL released), results in the
    list's order.

    Args:
        scenes: scenes (or files or dicts, loaded first).
        outputs: as in :func:`simulate`, for every scene.
        progress: a callable ``progress(phase, done, total)``, ``True`` for a tqdm bar,
            ``None`` for a tqdm bar when tqdm is installed, ``False`` for none.
        threads: worker threads (default: one per core).

    Raises:
        KeyboardInterrupt: on Ctrl-C (the simulations not started are skipped; nothing is
            returned).
    """
    loaded = [_scene(s) for s in scenes]
    results = _watched(_slipload.batch, progress, loaded, outputs=_outputs(outputs), threads=threads)
    _warn(results)
    return results


def batch_designs(
    scene: Union[None, PathLike, Dict[str, Any], Scene],
    records: Sequence[Record],
    slip_loads: Any,
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    outputs: Optional[Iterable[str]] = None,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """Runs one building under every record for every slip-load vector, in parallel.

    Each record runs with its own default step and duration (as a scene with that record
    would), unless ``method``/``dt`` say otherwise.

    Args:
        scene: the building: a :class:`Scene`, a scene or building file, a dict, or
            ``None`` for the benchmark building (its ground motion is replaced by each
            record).
        records: the suite.
        slip_loads: 2-D float64 array, shape (designs, dissipators): the slip loads, N,
            of the floors that carry a dissipator, in floor order (``scene.damper_floors``).
            Row d is design d in any memory order (C, Fortran, a transposed view); a
            strided view is refused.
        method, dt: as in :func:`simulate`.
        outputs: ``None`` or ``["energies"]`` (histories are not collected here).
        progress, threads: as in :func:`batch`.

    Returns:
        A dict of numpy arrays: per storey, shape (designs, records, storeys) —
        ``peak_drift`` (m), ``peak_drift_ratio``, ``peak_displacement`` (m),
        ``peak_abs_acceleration`` (m/s²), ``residual_drift`` (m), ``peak_slip`` (m),
        ``transitions``; per run, shape (designs, records) — ``peak_base_shear`` (N),
        ``collapsed`` (bool), ``cpu_seconds``, and with energies ``energy_input``,
        ``energy_friction``, ``energy_viscous``, ``energy_balance_error`` (J); and
        ``records`` (names), ``slip_loads``, ``damper_floors``.
    """
    records = list(records)
    if not isinstance(scene, Scene):
        # a building alone has no ground motion to resolve with: the first record stands in
        scene = load_scene(scene, record=records[0] if records else None)
    return _watched(
        _slipload.batch_designs,
        progress,
        scene,
        records,
        slip_loads,
        method=method,
        dt=dt,
        outputs=_outputs(outputs),
        threads=threads,
    )


# ------------------------------------------------------------------------------ studies


def load_study(study: Union[None, PathLike, Dict[str, Any], Study] = None) -> Study:
    """A study: a building, suites of records, a design space and an objective.

    Args:
        study: a study file (JSON), a dict with a study's fields (relative paths resolve
            from the current folder), a :class:`Study`, or ``None`` for the embedded
            benchmark study (``configs/study-benchmark.json``, the command line's default).

    Warns:
        UserWarning: what the study's inputs make doubtful (``Study.warnings``: a slip load
        or a base-shear limit that looks like kN written as N), as the command line warns.

    Raises:
        InputError: a bad file or field, with the message the command line prints.
    """
    if study is None:
        return Study.benchmark()
    if isinstance(study, Study):
        return study
    if isinstance(study, dict):
        loaded, name = Study.from_json(_json_text(study, "study (a dict)", "study"), "study (a dict)"), "study (a dict)"
    elif isinstance(study, (str, os.PathLike)):
        loaded, name = Study.load(os.fspath(study)), f"study {os.fspath(study)}"
    else:
        raise InputError(f"study: expected a file path, a dict, a slipload.Study or None, got a {type(study).__name__}")
    # the command line's "warning: study FILE, …" lines ("did you mean kN?")
    for text in loaded.warnings:
        warnings.warn(f"{name}, {text}", UserWarning, stacklevel=3)
    return loaded


# the design table's quantities given per dissipator (the others are per storey)
_PER_DISSIPATOR = ("slip_load_kn", "ratio_to_floor_weight", "ratio_to_weight_above", "friction_kn")


class StudyReport:
    """What a study call wrote and found.

    Attributes:
        out: the output folder.
        files: name → text of every JSON, CSV and Markdown file written.
        figures: names of the figure files written (SVG, PNG, CSV).
        optimum: ``optimum.json`` as a dict (``optimize`` only): slip loads (kN), the
            objective, finalists, which floors sit on a bound.
        design_table: the rows of ``design-table.json`` (``optimize`` only), a list of
            dicts; :meth:`design_table_frame` gives a pandas DataFrame.
        candidates: ``candidates.json`` (``optimize`` only).
        manifest: ``manifest.json`` (sweeps and optimizations).
        ranking: ``rank.json`` (``rank`` only).
        pareto: ``pareto.json`` (``optimize`` of a study with ``objectives``): the front,
            its knee, the extremes, the hypervolume and whether the front held at the
            check fidelity.
        pareto_table: the rows of ``pareto-table.json`` (the front's designs with the
            design table's columns and their ±25 % variants).
        code_check: ``code-check.json`` (``optimize`` of a study with ``limits``): the
            recommended design, every criterion at every suite and property case, the
            verdict (``passes``, ``verdict``, ``margin``); :meth:`check_frame` gives its
            lines as a pandas DataFrame, :meth:`compliance_frame` its compliance matrix.
        device_table: ``device-table.json`` (``optimize`` of a study with ``limits``): per
            damper the slip load's range, force, stroke, velocity, travel, cycles and energy
            the device must be specified for; :meth:`device_frame` gives a DataFrame, and
            :meth:`protocol_frame` the tests of ``devices.test_protocol``.
        details: everything else the call reported (simulations run and reused, …).
    """

    def __init__(self, raw: Dict[str, Any]) -> None:
        self.out: str = os.fspath(raw.pop("out"))
        self.files: Dict[str, str] = raw.pop("files")
        self.figures: List[str] = raw.pop("figures", [])
        self.details: Dict[str, Any] = raw

        def load(name: str) -> Any:
            text = self.files.get(name)
            return None if text is None else json.loads(text)

        self.optimum: Optional[Dict[str, Any]] = load("optimum.json")
        table = load("design-table.json")
        self.design_table: Optional[List[Dict[str, Any]]] = None if table is None else table["rows"]
        self.design_table_meta: Optional[Dict[str, Any]] = None if table is None else {k: v for k, v in table.items() if k != "rows"}
        self.candidates: Optional[List[Dict[str, Any]]] = load("candidates.json")
        self.manifest: Optional[Dict[str, Any]] = load("manifest.json")
        self.ranking: Optional[Dict[str, Any]] = load("rank.json")
        self.pareto: Optional[Dict[str, Any]] = load("pareto.json")
        ptable = load("pareto-table.json")
        self.pareto_table: Optional[List[Dict[str, Any]]] = None if ptable is None else ptable["rows"]
        self.code_check: Optional[Dict[str, Any]] = load("code-check.json")
        self.device_table: Optional[Dict[str, Any]] = load("device-table.json")

    @property
    def passes(self) -> Optional[bool]:
        """Whether the recommended design meets every limit (``None``: the study names none)."""
        return None if self.code_check is None else bool(self.code_check["passes"])

    def check_frame(self) -> Any:
        """The code check as a pandas DataFrame: one row per (suite, property case,
        criterion) with limit, demand, ratio, pass and the study key of the limit (needs
        pandas)."""
        import pandas as pd

        if self.code_check is None:
            raise InputError("this report has no code check (optimize writes one for a study with limits)")
        return pd.DataFrame(self.code_check["check"]["lines"])

    def device_frame(self) -> Any:
        """The device table as a pandas DataFrame, one row per damper (needs pandas)."""
        import pandas as pd

        if self.device_table is None:
            raise InputError("this report has no device table (optimize writes one for a study with limits)")
        return pd.DataFrame(self.device_table["dampers"]).set_index("floor")

    def compliance_frame(self) -> Any:
        """The code check's compliance matrix as a pandas DataFrame: one row per
        requirement with its clause, value, limit and status (``pass``, ``fail``,
        ``stated``, ``not_checked``, ``not_covered``; needs pandas)."""
        import pandas as pd

        if self.code_check is None:
            raise InputError("this report has no code check (optimize writes one for a study with limits)")
        return pd.DataFrame(self.code_check["compliance"])

    def protocol_frame(self) -> Any:
        """The device tests of ``devices.test_protocol`` as a pandas DataFrame, one row per
        damper: amplitude, the sinusoid's velocity, and the force at zero displacement and
        loop energy with their bounds (needs pandas)."""
        import pandas as pd

        protocol = None if self.device_table is None else self.device_table.get("test_protocol")
        if protocol is None:
            raise InputError("this report has no test protocol (give the study devices.test_protocol)")
        rows = []
        for d in protocol["dampers"]:
            row = {"floor": d["floor"], "amplitude_mm": d["amplitude_mm"], "velocity_mm_s": d.get("velocity_mm_s")}
            for i, case in enumerate(("nominal", "lower", "upper")):
                row[f"force_kn_{case}"] = d["force_kn"][i]
                row[f"loop_energy_kj_{case}"] = d["loop_energy_kj"][i]
            rows.append(row)
        return pd.DataFrame(rows).set_index("floor")

    def design_table_frame(self) -> Any:
        """The design table as a pandas DataFrame, one row per design, indexed by the
        design's name, one number per cell (needs pandas).

        A quantity given per dissipator takes one column per floor that carries one,
        named by that floor (from 1): ``slip_load_kn_floor_1``, …,
        ``ratio_to_floor_weight_floor_1``, ``ratio_to_weight_above_floor_1`` (and
        ``friction_kn_floor_1`` for a design whose friction law a slip load cannot say).
        A quantity given per storey takes one column per storey (from 1):
        ``drift_ratio_mean_storey_1``, ``drift_ratio_p84_storey_1``,
        ``drift_ratio_max_storey_1``, ``stroke_max_storey_1``. The other columns are
        those of ``design-table.json``'s rows (``objective``, ``peak_drift_ratio_mean``,
        ``base_shear_mean``, …)."""
        import pandas as pd

        if self.design_table is None:
            raise InputError("this report has no design table (optimize writes one)")
        floors = list((self.design_table_meta or {}).get("damper_floors") or [])
        rows = []
        for row in self.design_table:
            flat: Dict[str, Any] = {}
            for key, value in row.items():
                if not isinstance(value, list):
                    flat[key] = value
                elif key in _PER_DISSIPATOR and len(value) == len(floors):
                    flat.update((f"{key}_floor_{f}", v) for f, v in zip(floors, value))
                else:
                    flat.update((f"{key}_storey_{i}", v) for i, v in enumerate(value, start=1))
            rows.append(flat)
        return pd.DataFrame(rows).set_index("design")

    def __repr__(self) -> str:
        what = ", ".join(sorted(self.files))
        return f"StudyReport(out={self.out!r}, files: {what})"


def optimize(
    study: Union[None, PathLike, Dict[str, Any], Study] = None,
    out: PathLike = "out/optimize",
    *,
    refine: Optional[str] = None,
    map_floors: Optional[Tuple[int, int]] = None,
    map_grid: int = 11,
    fresh: bool = False,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> Union[StudyReport, Dict[str, Any]]:
    """Optimises a study's slip loads, as ``slipload optimize`` does: sweep, refine from the
    best sweep points, check the finalists at reference accuracy, build the design table,
    draw the figures — into ``out``, journalled and resumable.

    Args:
        study: see :func:`load_study` (``None``: the embedded benchmark study).
        out: output folder (created if missing). A finished sweep there is reused and
            journalled refinement points replayed; a folder of another study is refused.
        refine: ``"auto"``, ``"model"``, ``"sqp"``, ``"trust-region"``, ``"nelder-mead"`` or ``"random"``
            (default: the study's).
        map_floors: also draw the objective map over these two floors' slip loads (from 1).
        map_grid: grid points per axis of the map.
        fresh: first remove every file a slipload command wrote in ``out``.
        progress, threads: as in :func:`batch`.

    Returns:
        A :class:`StudyReport` (``optimum``, ``design_table``, ``candidates``, …). The files
        are byte for byte those the command line writes for the same study.

        A study in plan (a file whose building is a building in plan) runs as the command
        line runs it and gives a dict: ``summary`` (the text of ``plan-summary.txt``),
        ``files``, ``figures``, ``replayed``, ``sweep_designs``, ``refine_designs``
        (``refine`` must be ``None`` or ``"model"``; no objective map).

    Raises:
        KeyboardInterrupt: on Ctrl-C; every simulation already finished is in the folder's
            journals and is not run again by the next call.
    """
    if isinstance(study, (str, os.PathLike)) and _slipload.is_plan_study(os.fspath(study)):
        if refine not in (None, "model", "auto"):
            raise ValueError(
                f"refine={refine!r}: a study in plan refines with 'model' (its runs compute no sensitivities for sqp)"
            )
        if map_floors is not None:
            raise ValueError(
                "map_floors: a study in plan draws no objective map (its figures are the plan view and the drift profiles by line)"
            )
        return _watched(
            _slipload.optimize_in_plan,
            progress,
            os.fspath(study),
            os.fspath(out),
            fresh=fresh,
            threads=threads,
        )
    raw = _watched(
        _slipload.optimize,
        progress,
        load_study(study),
        os.fspath(out),
        refine=refine,
        map_floors=map_floors,
        map_grid=map_grid,
        fresh=fresh,
        threads=threads,
    )
    return StudyReport(raw)


def sweep(
    study: Union[PathLike, Dict[str, Any], Study],
    out: PathLike = "out/sweep",
    *,
    shard: Optional[str] = None,
    resume: bool = False,
    fresh: bool = False,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> StudyReport:
    """Sweeps a study's sample of designs over every record, as ``slipload sweep`` does.

    Args:
        study: see :func:`load_study`.
        out: output folder: ``manifest.json``, ``responses.csv``, ``designs.csv``,
            ``journal.jsonl`` and the sweep's figures.
        shard: run one slice of the tasks, ``"I/N"`` (from 0) or ``"auto"`` (a job
            array's environment).
        resume: continue the journal in ``out`` (a journal of the same study only).
        fresh: first remove every file a slipload command wrote in ``out``.
        progress, threads: as in :func:`batch`.
    """
    raw = _watched(
        _slipload.sweep,
        progress,
        load_study(study),
        os.fspath(out),
        shard=shard,
        resume=resume,
        fresh=fresh,
        threads=threads,
    )
    return StudyReport(raw)


def merge(dirs: Sequence[PathLike], out: PathLike) -> StudyReport:
    """Joins the journals of sweep shards into the files one sweep writes, as
    ``slipload merge`` does."""
    return StudyReport(_slipload.merge([os.fspath(d) for d in dirs], os.fspath(out)))


def rank(
    study: Union[PathLike, Dict[str, Any], Study],
    designs: Union[PathLike, List[Dict[str, Any]]],
    out: PathLike = "out/rank",
    *,
    bootstrap: int = 200,
    seed: int = 1,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> StudyReport:
    """Ranks candidate designs over every suite of a study, with a bootstrap over the
    records for how stable the ranking is, as ``slipload rank`` does.

    Args:
        study: see :func:`load_study`.
        designs: a candidates file (as ``optimize`` writes ``candidates.json``) or a list
            of ``{"name": ..., "slip_loads_kn": [...]}`` dicts.
        out: output folder: ``rank.csv``, ``rank.md``, ``rank.json``.
        bootstrap: resamples of the records.
        seed: the bootstrap's seed.
    """
    if isinstance(designs, list):
        import tempfile

        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "designs.json")
            with open(path, "w", encoding="utf-8") as f:
                f.write(_json_text(designs, "designs (a list)", "designs"))
            return rank(study, path, out, bootstrap=bootstrap, seed=seed, progress=progress, threads=threads)
    raw = _watched(
        _slipload.rank,
        progress,
        load_study(study),
        os.fspath(designs),
        os.fspath(out),
        bootstrap=bootstrap,
        seed=seed,
        threads=threads,
    )
    return StudyReport(raw)


def table(
    study: Union[None, PathLike, Dict[str, Any], Study] = None,
    out: PathLike = "out/table",
    *,
    period_scales: Sequence[float] = (0.8, 1.0, 1.25),
    intensity_scales: Sequence[float] = (0.5, 1.0, 1.5),
    refine: Optional[str] = None,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> StudyReport:
    """The optimum of a study over a family of buildings (periods scaled) and hazard levels
    (records scaled), as ``slipload table`` does: ``family.csv`` and ``family.md``."""
    raw = _watched(
        _slipload.table,
        progress,
        load_study(study),
        os.fspath(out),
        period_scales=list(period_scales),
        intensity_scales=list(intensity_scales),
        refine=refine,
        threads=threads,
    )
    return StudyReport(raw)


def evaluate_objectives(
    study: Union[PathLike, Dict[str, Any], Study],
    slip_loads: Any,
    *,
    progress: Progress = None,
    threads: Optional[int] = None,
) -> Any:
    """The objective vectors of designs under a study's ``objectives`` (2 to 4), at the
    study's sweep fidelity — the evaluations its front search makes, for driving another
    optimiser (pymoo, say) with slipload's simulations.

    Args:
        study: a study with ``objectives`` (see :func:`load_study`).
        slip_loads: 2-D float64 array (designs, dissipators), N, in the order of the
            study's ``damper_floors``; row d is design d in any memory order (C,
            Fortran, a transposed view); a strided view is refused.
        progress, threads: as in :func:`batch`.

    Returns:
        A float64 array (designs, objectives), minimised; a design that collapses on a
        record scores +inf in every objective. Each design runs every record of the study.
    """
    return _watched(_slipload.evaluate_objectives, progress, load_study(study), slip_loads, threads=threads)


def _is_empty(points: Any) -> bool:
    """Whether ``points`` holds no point: an array of size 0 or an empty list or tuple."""
    if isinstance(points, (list, tuple)):
        return len(points) == 0
    return getattr(points, "size", None) == 0


def nondominated_ranks(points: Any) -> List[int]:
    """Non-dominated ranks of the rows of a 2-D float64 array (minimisation): 1 for the
    front, 2 for the front of the rest, and so on; equal points share a rank. A design
    that collapsed scores +inf (as :func:`evaluate_objectives` gives it) and ranks behind
    every design it is worse than; NaN and -inf are refused. No points: an empty list."""
    if _is_empty(points):
        return []
    return _slipload.nondominated_ranks(points)


def hypervolume(points: Any, reference: Any) -> float:
    """The hypervolume (area, volume) the rows of ``points`` dominate up to ``reference``
    (minimisation, 1 to 4 objectives; exact): the measure the study reports compare fronts
    by. Points not below the reference in every objective add nothing."""
    return _slipload.hypervolume(points, reference)


def knee(points: Any) -> Optional[int]:
    """The index of the knee of a front (rows of a 2-D float64 array, minimisation) by the
    rule the study reports use: the point of least sum of objectives, each normalised to
    0 at the front's best and 1 at its worst. ``None`` for an empty front (an array of
    size 0, ``[]``)."""
    if _is_empty(points):
        return None
    return _slipload.knee(points)


def allow_large(on: bool = True) -> None:
    """Lifts (``True``) or restores (``False``) the size limits on inputs — records,
    suites, steps — as the command line's ``--allow-large`` does."""
    _slipload.allow_large(on)
