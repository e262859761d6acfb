"""Type stubs of the native module ``slipload._slipload`` (the Rust engine).

Use the package's functions (``slipload.simulate``, ``slipload.optimize``, …); the classes
below are re-exported there. Units are SI: m, s, N, kg; accelerations in m/s².
"""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
NUMERICS_VERSION: int
MAX_CONFIG_BYTES: int

FloatArray = npt.NDArray[np.float64]
ProgressCallback = Optional[Callable[[str, int, int], Any]]

class Record:
    """A ground-motion record: accelerations at a uniform time step, held in m/s²."""

    @staticmethod
    def read(path: str, units: Optional[str] = None, dt: Optional[float] = None) -> "Record":
        """Reads a PEER .AT2 file or a CSV/text file."""
    @staticmethod
    def from_array(accel: FloatArray, dt: float, units: str = "m/s2", name: str = "array") -> "Record":
        """A record from a 1-D float64 array of accelerations (``units``) at step ``dt`` (s)."""
    @property
    def name(self) -> str:
        """The record's name."""
    @property
    def dt(self) -> float:
        """Time step, s."""
    @property
    def npts(self) -> int:
        """Number of samples."""
    @property
    def duration(self) -> float:
        """Duration, s."""
    @property
    def pga(self) -> float:
        """Peak ground acceleration, m/s²."""
    @property
    def pga_g(self) -> float:
        """Peak ground acceleration, g."""
    @property
    def notes(self) -> List[str]:
        """What the reader said about the file, one sentence each (units given that
        override an AT2 title's); empty for most records."""
    @property
    def scale_factor(self) -> float:
        """Product of the factors the record was scaled by since it was read or built (1 as
        read); the PGA before scaling is ``pga / scale_factor``."""
    @property
    def accel(self) -> FloatArray:
        """Accelerations, m/s² (a copy)."""
    @property
    def time(self) -> FloatArray:
        """Sample times, s."""
    def __len__(self) -> int: ...
    def scaled(self, factor: float) -> "Record":
        """The record times ``factor``."""
    def scaled_to_pga(self, pga_g: float) -> "Record":
        """The record scaled to a peak ground acceleration, in g."""
    def window(self, start: float, duration: float) -> "Record":
        """The part of the record from ``start`` lasting ``duration``, s."""
    def spectrum(self, periods: Optional[FloatArray] = None, damping: float = 0.05) -> Dict[str, Any]:
        """Response spectrum at ``periods`` (s; default 60 log-spaced from 0.02 to 5 s) for
        damping ratio ``damping``: ``periods``, ``sd`` (m), ``psv`` (m/s), ``psa`` (m/s²)."""
    def intensity(self) -> Dict[str, float]:
        """Intensity measures: ``pga`` (m/s²), ``pgv`` (m/s), ``pgd`` (m), ``arias`` (m/s),
        ``d5_95`` (s)."""

class Scene:
    """A resolved scene: a building under a ground motion, with its method and outputs."""

    @staticmethod
    def load(
        path: str,
        *,
        record: Any = None,
        units: Optional[str] = None,
        scale_pga_g: Optional[float] = None,
        scale: Optional[float] = None,
        window: Optional[Tuple[float, float]] = None,
        method: Optional[str] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Scene":
        """Loads a scene or building file."""
    @staticmethod
    def from_json(
        text: str,
        name: str = "scene",
        *,
        record: Any = None,
        units: Optional[str] = None,
        scale_pga_g: Optional[float] = None,
        scale: Optional[float] = None,
        window: Optional[Tuple[float, float]] = None,
        method: Optional[str] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Scene":
        """A scene from JSON text (a scene file's or a building file's)."""
    @staticmethod
    def benchmark(
        *,
        record: Any = None,
        units: Optional[str] = None,
        scale_pga_g: Optional[float] = None,
        scale: Optional[float] = None,
        window: Optional[Tuple[float, float]] = None,
        method: Optional[str] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Scene":
        """The embedded benchmark building under the first record of the embedded suite."""
    def replace(
        self,
        *,
        record: Any = None,
        units: Optional[str] = None,
        scale_pga_g: Optional[float] = None,
        scale: Optional[float] = None,
        window: Optional[Tuple[float, float]] = None,
        method: Optional[str] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Scene":
        """The same scene with other overrides (those not given are kept)."""
    def with_slip_loads(self, slip_loads: FloatArray) -> "Scene":
        """The same scene with other slip loads, N: one per dissipator, in floor order."""
    @property
    def name(self) -> str:
        """The scene's name."""
    @property
    def floors(self) -> int:
        """Number of storeys."""
    @property
    def damper_floors(self) -> List[int]:
        """Floors (from 1) that carry a dissipator."""
    @property
    def slip_loads(self) -> FloatArray:
        """Slip loads of the dissipators, N, in floor order (inf: locked)."""
    @property
    def periods(self) -> FloatArray:
        """Natural periods of the bare frame, s (longest first)."""
    @property
    def method(self) -> str:
        """The integration method's name."""
    @property
    def dt(self) -> float:
        """Time step, s."""
    @property
    def duration(self) -> float:
        """Simulated time, s."""
    @property
    def steps(self) -> int:
        """Number of steps."""
    @property
    def record(self) -> Optional[Record]:
        """The ground motion (None for a scene without one)."""
    @property
    def notes(self) -> List[str]:
        """Notes the loader made (a run past the record's end, say)."""

class History:
    """Time histories: one row per step (time first), one column per quantity."""

    @property
    def columns(self) -> List[str]:
        """Column names with their units (``t_s``, ``ag_m_s2``, ``x1_m``, …)."""
    @property
    def array(self) -> npt.NDArray[np.float64]:
        """The values, shape (steps + 1, columns)."""
    @property
    def time(self) -> FloatArray:
        """Time, s (the first column)."""
    def __len__(self) -> int: ...
    def __getitem__(self, name: str) -> FloatArray: ...
    def to_pandas(self) -> Any:
        """A pandas DataFrame of the histories (needs pandas)."""
    def to_csv(self) -> str:
        """The history as CSV text, as ``slipload simulate --history`` writes it."""

class Result:
    """One simulation's responses (SI units), as ``slipload simulate`` reports them."""

    @property
    def method(self) -> str:
        """The method that ran."""
    @property
    def warnings(self) -> List[str]:
        """What the run's inputs make doubtful without making them wrong (a slip load
        below 0.1 % of its floor's weight, a step past the duration), as ``slipload
        simulate`` prints them; ``simulate`` and ``batch`` warn them as ``UserWarning``."""
    @property
    def dt(self) -> float:
        """Time step, s."""
    @property
    def steps(self) -> int:
        """Steps taken."""
    @property
    def cpu_seconds(self) -> float:
        """CPU time of the run, s."""
    @property
    def peak_drift(self) -> FloatArray:
        """Peak |interstorey drift| per storey, m."""
    @property
    def peak_drift_ratio(self) -> Optional[FloatArray]:
        """Peak drift ratio per storey; None without storey heights."""
    @property
    def peak_displacement(self) -> FloatArray:
        """Peak |floor displacement| relative to the ground per floor, m."""
    @property
    def peak_abs_acceleration(self) -> FloatArray:
        """Peak |absolute floor acceleration| per floor, m/s²."""
    @property
    def residual_drift(self) -> FloatArray:
        """Interstorey drift at the end of the run per storey, m."""
    @property
    def peak_base_shear(self) -> float:
        """Peak |base shear|, N."""
    @property
    def peak_slip(self) -> FloatArray:
        """Peak |slip| of each storey's dissipator, m."""
    @property
    def transitions(self) -> npt.NDArray[np.uint64]:
        """Stick↔slip transitions per storey."""
    @property
    def energy(self) -> Optional[Dict[str, Optional[float]]]:
        """Energies at the end, J (None unless asked)."""
    @property
    def peak_ductility(self) -> Optional[FloatArray]:
        """Peak ductility per storey (NaN without a yield law); None for an elastic frame."""
    @property
    def peak_plastic_drift(self) -> Optional[FloatArray]:
        """Peak plastic drift per storey, m; None for an elastic frame."""
    @property
    def collapse(self) -> Optional[Dict[str, float]]:
        """The collapse the run stopped on (storey, time s, drift m, limit m), or None."""
    @property
    def collapsed(self) -> bool:
        """Whether the run stopped on the collapse limit."""
    @property
    def history(self) -> Optional[History]:
        """The histories (None unless asked for)."""
    def to_json(self) -> str:
        """The output contract's JSON, as ``slipload simulate --format json`` prints it."""

class Study:
    """A validated study: its building, records, design space and objective."""

    @staticmethod
    def load(path: str) -> "Study":
        """Loads a study file."""
    @staticmethod
    def from_json(text: str, name: str = "study") -> "Study":
        """A study from JSON text."""
    @staticmethod
    def benchmark() -> "Study":
        """The embedded benchmark study."""
    @property
    def warnings(self) -> List[str]:
        """What the study's inputs make doubtful (the command line's warnings)."""
    @property
    def name(self) -> str:
        """The study's name."""
    @property
    def objective(self) -> str:
        """The objective, as a label."""
    @property
    def damper_floors(self) -> List[int]:
        """Floors (from 1) of the design's dissipators."""
    @property
    def file_slip_loads(self) -> List[float]:
        """The building file's slip loads, N per dissipator."""
    @property
    def records(self) -> List[Record]:
        """The records of every suite, in order."""
    @property
    def suites(self) -> List[Tuple[str, int]]:
        """The suites: name and number of records."""
    @property
    def fingerprint(self) -> str:
        """The study's fingerprint (what its journals are keyed by)."""

def synthetic_suite(
    count: Optional[int] = None,
    seed: Optional[int] = None,
    pga_g: Optional[float] = None,
    duration: Optional[float] = None,
    dt: Optional[float] = None,
) -> List[Record]:
    """Synthetic ground motions (default: the embedded suite)."""

def simulate(
    scene: Scene,
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
    outputs: Optional[Sequence[str]] = None,
) -> Result:
    """Runs one scene."""

def simulate_in_plan(
    path: str,
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
    outputs: Optional[Sequence[str]] = None,
) -> Result:
    """Runs the scene in plan at `path`."""

def is_in_plan(path: str) -> bool:
    """Whether the file is a scene in plan or a building in plan."""

def is_plan_study(path: str) -> bool:
    """Whether the file is a study in plan (its building is a building in plan)."""

def optimize_in_plan(
    path: str,
    out: str,
    *,
    fresh: bool = False,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """Optimises the study in plan at `path` into `out`, as `slipload optimize` does."""

def batch(
    scenes: Sequence[Scene],
    *,
    outputs: Optional[Sequence[str]] = None,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> List[Result]:
    """Runs every scene of a list in parallel."""

def batch_designs(
    scene: Scene,
    records: Sequence[Record],
    slip_loads: npt.NDArray[np.float64],
    *,
    method: Optional[str] = None,
    dt: Optional[float] = None,
    outputs: Optional[Sequence[str]] = None,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """One building × records × slip-load vectors, in parallel."""

def optimize(
    study: Optional[Study] = None,
    out: str = "out/optimize",
    *,
    refine: Optional[str] = None,
    map_floors: Optional[Tuple[int, int]] = None,
    map_grid: Optional[int] = None,
    fresh: bool = False,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """``slipload optimize``."""

def sweep(
    study: Study,
    out: str = "out/sweep",
    *,
    shard: Optional[str] = None,
    resume: bool = False,
    fresh: bool = False,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """``slipload sweep``."""

def merge(dirs: Sequence[str], out: str) -> Dict[str, Any]:
    """``slipload merge``."""

def rank(
    study: Study,
    designs: str,
    out: str = "out/rank",
    *,
    bootstrap: Optional[int] = None,
    seed: Optional[int] = None,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """``slipload rank``."""

def table(
    study: Optional[Study] = None,
    out: str = "out/table",
    *,
    period_scales: Sequence[float] = ...,
    intensity_scales: Sequence[float] = ...,
    refine: Optional[str] = None,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """``slipload table``."""

def evaluate_objectives(
    study: Study,
    slip_loads: npt.NDArray[np.float64],
    *,
    progress: ProgressCallback = None,
    threads: Optional[int] = None,
) -> npt.NDArray[np.float64]:
    """Objective vectors (designs, objectives) of a study with ``objectives``."""

def nondominated_ranks(points: npt.NDArray[np.float64]) -> List[int]:
    """Non-dominated ranks (1 = the front), minimisation."""

def hypervolume(points: npt.NDArray[np.float64], reference: FloatArray) -> float:
    """The hypervolume dominated up to ``reference``, minimisation, 1 to 4 objectives."""

def knee(points: npt.NDArray[np.float64]) -> Optional[int]:
    """The knee of a front by the study reports' rule."""

def allow_large(on: bool) -> None:
    """Lifts or restores the size limits on inputs."""

def dict_json(value: Any, name: str, what: str) -> str:
    """A dict or list given for a ``what`` file as JSON text, refused by field path as the
    command line refuses the same file (size, depth, NaN/inf, values JSON has none of)."""
