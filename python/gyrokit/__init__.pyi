# Type hints of the package gyrokit (see docs/python.md).
from os import PathLike
from typing import Any, Literal, Mapping, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

# The bound classes: their stubs are generated from the bindings (_core.pyi).
from ._core import Bearing as Bearing, Disk as Disk, Error as Error, InputError as InputError
from ._core import Pedestal as Pedestal, Rotor as Rotor, Scene as Scene, Section as Section
from ._core import SolverError as SolverError, Support as Support, System as System
from ._core import __version__ as __version__, coupling as coupling
from ._core import Material as Material, materials as materials
from ._core import FluidRotorParameters as FluidRotorParameters, GyrostatParameters as GyrostatParameters

Model = Union[System, Scene]
Path = Union[str, PathLike[str]]

class Table:
    key: str
    title: str
    columns: list[str]
    rows: list[list[Any]]
    def __init__(self, key: str, title: str, columns: Sequence[str], rows: Sequence[Sequence[Any]]) -> None: ...
    def column(self, name: str) -> list[Any]: ...
    def to_pandas(self) -> Any: ...

def load_tables(path: Path) -> list[Table]: ...
def draw(figure: Mapping[str, Any], axes: Any = ...) -> Any: ...

class _Result:
    tables: Sequence[Table]
    def __init__(self, d: dict[str, Any]) -> None: ...   # made by the analysis functions, from _core's result
    def table(self, key: str) -> Table: ...
    def save(self, path: Path, table: Optional[str] = ...) -> Path: ...
    def plot(self, path: Optional[Path] = ..., axes: Any = ...) -> Any: ...

class ModeShapes(_Result):
    unit: str
    speed: float
    eigenvalues: npt.NDArray[np.complex128]
    frequencies: npt.NDArray[np.float64]
    shapes: npt.NDArray[np.complex128]
    numbers: list[int]
    reference: list[str]
    whirl: list[str]
    dof_names: list[str]
    orbits: dict[str, Any]
    damping_ratios: npt.NDArray[np.float64]
    log_decrements: npt.NDArray[np.float64]
    notes: list[str]
    def to_pandas(self) -> Any: ...
    def plot(self, path: Optional[Path] = ..., axes: Any = ..., mode: Union[int, Sequence[int], None] = ...) -> Any: ...
    def plot_orbits(self, mode: Optional[int] = ..., ax: Any = ...) -> Any: ...

class EigResult(_Result):
    unit: str
    speed: float
    eigenvalues: npt.NDArray[np.complex128]
    frequencies: npt.NDArray[np.float64]
    damping_ratios: npt.NDArray[np.float64]
    log_decrements: npt.NDArray[np.float64]
    backward_errors: npt.NDArray[np.float64]
    error_bounds: npt.NDArray[np.float64]
    whirl: list[str]
    stability: list[str]
    vectors: npt.NDArray[np.complex128]
    rigid_body: npt.NDArray[np.complex128]
    method: str
    notes: list[str]
    def to_pandas(self) -> Any: ...

class CampbellResult(_Result):
    unit: str
    speeds: npt.NDArray[np.float64]
    eigenvalues: npt.NDArray[np.complex128]
    frequencies: npt.NDArray[np.float64]
    damping_ratios: npt.NDArray[np.float64]
    log_decrements: npt.NDArray[np.float64]
    backward_errors: npt.NDArray[np.float64]
    whirl: list[list[str]]
    branches: npt.NDArray[np.int32]
    judged_branches: npt.NDArray[np.int32]   # the modes up to f_cut beyond the K shown (ids K + 1 on)
    judged_eigenvalues: npt.NDArray[np.complex128]   # speeds x judged_branches
    inserted_speeds: int
    ambiguous_steps: int
    max_backward_error: float
    rigid_body: int
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

class CriticalSpeeds(_Result):
    unit: str
    speeds: npt.NDArray[np.float64]
    bounds: npt.NDArray[np.float64]
    harmonic: npt.NDArray[np.int32]
    branch: npt.NDArray[np.int32]
    whirl: list[str]
    damping_ratio: npt.NDArray[np.float64]
    log_dec: npt.NDArray[np.float64]
    amplification: npt.NDArray[np.float64]
    af_method: list[str]
    af_dof: list[str]
    af_note: list[str]
    api684_critical: npt.NDArray[np.bool_]
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

class StabilityChanges(_Result):
    unit: str
    speeds: npt.NDArray[np.float64]
    bounds: npt.NDArray[np.float64]
    branch: npt.NDArray[np.int32]
    becomes_unstable: npt.NDArray[np.bool_]
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

def defaults() -> list[dict[str, str]]: ...

def load_scene(path: Union[str, PathLike[str]], overrides: Optional[Mapping[str, float]] = ...,
               motion: Optional[str] = ...) -> Scene: ...
def modes(model: Model, speed: float, *, solver: Optional[str] = ..., modes: Optional[int] = ...,
          target: Optional[float] = ..., target_order: Optional[float] = ..., method: str = ...,
          lanczos: int = ..., unit: Optional[str] = ...) -> ModeShapes: ...
def eig(model: Model, speed: float, *, solver: Optional[str] = ..., modes: Optional[int] = ...,
        target: Optional[float] = ..., target_order: Optional[float] = ..., method: str = ...,
        lanczos: int = ..., unit: Optional[str] = ...) -> EigResult: ...
def campbell(model: Model, speeds: Optional[npt.ArrayLike] = ..., *, harmonics: Optional[Sequence[int]] = ...,
             solver: Optional[str] = ...,
             modes: Optional[int] = ..., target: Optional[float] = ..., target_order: Optional[float] = ...,
             method: str = ..., lanczos: int = ..., jobs: int = ..., unit: Optional[str] = ...,
             f_cut: Optional[float] = ...) -> CampbellResult: ...
def critical_speeds(model: Model, speeds: Optional[npt.ArrayLike] = ..., *, harmonics: Optional[Sequence[int]] = ...,
                    solver: Optional[str] = ..., modes: Optional[int] = ..., target: Optional[float] = ...,
                    target_order: Optional[float] = ..., method: str = ..., lanczos: int = ...,
                    jobs: int = ..., unit: Optional[str] = ..., f_cut: Optional[float] = ...) -> CriticalSpeeds: ...
def stability(model: Model, speeds: Optional[npt.ArrayLike] = ..., *, harmonics: Optional[Sequence[int]] = ...,
              solver: Optional[str] = ...,
              modes: Optional[int] = ..., target: Optional[float] = ..., target_order: Optional[float] = ...,
              method: str = ..., lanczos: int = ..., jobs: int = ..., unit: Optional[str] = ...,
              f_cut: Optional[float] = ...) -> StabilityChanges: ...

class ScreenResult:
    def __init__(self, d: dict[str, Any]) -> None: ...
    columns: list[str]
    design: npt.NDArray[np.int_]
    parameters: dict[str, npt.NDArray[np.float64]]
    quantities: dict[str, npt.NDArray[np.float64]]
    labels: dict[str, list[Optional[str]]]
    verdict: list[str]
    failed: list[list[str]]
    reason: list[str]
    unit: str
    @property
    def passed(self) -> npt.NDArray[np.bool_]: ...
    def to_pandas(self) -> Any: ...
    def plot(self, x: Optional[str] = ..., y: Optional[str] = ..., ax: Any = ...) -> Any: ...

def screen(sweep: Union[str, PathLike[str]], designs: Optional[Sequence[Mapping[str, float]]] = ..., *,
           scene: Optional[Scene] = ..., jobs: int = ..., progress: Optional[Any] = ...,
           executor: Optional[Any] = ..., retries: int = ...) -> ScreenResult: ...

class PervasiveLosses(_Result):
    unit: str
    checked: list[str]
    checked_speeds: int
    checked_modes: int
    f_cut: Optional[float]
    pervades: bool
    partial: bool
    damping: list[str]
    speeds: npt.NDArray[np.float64]
    mode: npt.NDArray[np.int32]
    frequency: npt.NDArray[np.float64]
    whirl: list[str]
    residual: npt.NDArray[np.float64]
    notes: list[str]
    def to_pandas(self) -> Any: ...

class Response(_Result):
    def __init__(self, speeds: npt.ArrayLike, dofs: Sequence[str], Z: npt.ArrayLike,
                 d: Optional[dict[str, Any]] = ..., unit: str = ...) -> None: ...
    unit: str
    speeds: npt.NDArray[np.float64]
    dofs: list[str]
    amplitudes: npt.NDArray[np.complex128]
    amplitude: npt.NDArray[np.float64]
    phase: npt.NDArray[np.float64]  # degrees
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...
    def plot_polar(self, path: Optional[Path] = ..., axes: Any = ...) -> Any: ...

def pervasive(model: Model, speeds: Optional[npt.ArrayLike] = ..., *, tolerance: float = ...,
              solver: Optional[str] = ..., modes: Optional[int] = ..., target: Optional[float] = ...,
              target_order: Optional[float] = ..., method: str = ..., lanczos: int = ...,
              jobs: int = ..., unit: Optional[str] = ...) -> PervasiveLosses: ...
def response(model: Model, speeds: Optional[npt.ArrayLike] = ..., *, dofs: Optional[Sequence[str]] = ...,
             probes: Optional[Sequence[tuple[int, float]]] = ...,
             solver: Optional[str] = ..., harmonics: Optional[Sequence[int]] = ...,
             modes: Optional[int] = ..., method: str = ..., lanczos: int = ..., jobs: int = ...,
             unit: Optional[str] = ..., f_cut: Optional[float] = ..., stability_check: bool = ...,
             extrema: bool = ..., peaks: bool = ...) -> Response: ...
def gyrostat(parameters: Optional[GyrostatParameters] = ..., *, title: str = ...,
             speeds: Optional[Mapping[str, Union[float, str]]] = ..., analysis: Optional[Mapping[str, Any]] = ...,
             **keys: Any) -> Scene: ...
def fe_rotor(*, speeds: Optional[Mapping[str, Union[float, str]]] = ..., analysis: Optional[Mapping[str, Any]] = ...,
             directory: str = ..., **keys: Any) -> Scene: ...
def rotor_scene(rotor: Rotor, *, title: str = ..., speeds: Optional[Mapping[str, Union[float, str]]] = ...,
                analysis: Optional[Mapping[str, Any]] = ...) -> Scene: ...

def fluid_rotor(parameters: Optional[FluidRotorParameters] = ..., *, title: str = ...,
                speeds: Optional[Mapping[str, Union[float, str]]] = ..., analysis: Optional[Mapping[str, Any]] = ...,
                **keys: Any) -> Scene: ...
def matrices_scene(directory: str, *, speeds: Optional[Mapping[str, Union[float, str]]] = ...,
                   analysis: Optional[Mapping[str, Any]] = ..., **keys: Any) -> Scene: ...

class FluidResult(_Result):
    unit: str
    fills: Optional[npt.NDArray[np.float64]]
    critical_speeds: dict[str, Any]
    J_eq: float
    J_eq_rigid: float
    notes: list[str]

def fluid(scene: Scene, *, fill: Optional[npt.ArrayLike] = ..., unit: Optional[str] = ...) -> FluidResult: ...

class BalancerStates(_Result):
    state: list[str]
    alpha_deg: list[npt.NDArray[np.float64]]
    range: list[str]
    range_from: npt.NDArray[np.float64]
    range_to: npt.NDArray[np.float64]
    stable: list[bool]
    stable_eigen: list[bool]
    max_real_eigenvalue: npt.NDArray[np.float64]
    compensating: list[bool]
    ranges: list[dict[str, Any]]   # range, from, to, balances, stable_compensating, stable_other, disputed
    def to_pandas(self) -> Any: ...

class BalancerRun(_Result):
    t: npt.NDArray[np.float64]
    speed: npt.NDArray[np.float64]
    radius: npt.NDArray[np.float64]
    alpha: list[npt.NDArray[np.float64]]
    final_alpha: list[float]
    final_speed: float
    residual_rms: float
    residual_max: float
    def to_pandas(self) -> Any: ...

class SommerfeldRunup(_Result):
    t: npt.NDArray[np.float64]
    nominal: npt.NDArray[np.float64]
    rotor_speed: npt.NDArray[np.float64]
    amplitude: npt.NDArray[np.float64]
    held_rotor_speed: float
    held_amplitude: float
    final_rotor_speed: float
    def to_pandas(self) -> Any: ...

class Sommerfeld(_Result):
    limit_speed_estimate: float
    has_jump: bool
    folds: list[dict[str, Any]]
    jump_up: Optional[float]
    jump_up_rotor_speed: Optional[float]
    jump_down: Optional[float]
    jump_down_rotor_speed: Optional[float]
    def to_pandas(self) -> Any: ...

@overload
def balancer(scene: Union[str, PathLike[str]], *, simulate: Literal[False] = ..., averaged: bool = ...,
             speed: Optional[float] = ..., duration: Optional[float] = ..., integrator: Optional[str] = ...,
             abs_tol: Optional[float] = ..., rel_tol: Optional[float] = ..., history: bool = ...) -> BalancerStates: ...
@overload
def balancer(scene: Union[str, PathLike[str]], *, simulate: Literal[True], averaged: bool = ...,
             speed: Optional[float] = ..., duration: Optional[float] = ..., integrator: Optional[str] = ...,
             abs_tol: Optional[float] = ..., rel_tol: Optional[float] = ..., history: bool = ...) -> BalancerRun: ...
@overload
def sommerfeld(scene: Union[str, PathLike[str]], *, speeds: Optional[tuple[float, float, int]] = ...,
               runup: Literal[False] = ..., integrator: Optional[str] = ..., abs_tol: Optional[float] = ...,
               rel_tol: Optional[float] = ..., max_speed: Optional[float] = ...) -> Sommerfeld: ...
@overload
def sommerfeld(scene: Union[str, PathLike[str]], *, speeds: Optional[tuple[float, float, int]] = ...,
               runup: Literal[True], integrator: Optional[str] = ..., abs_tol: Optional[float] = ...,
               rel_tol: Optional[float] = ..., max_speed: Optional[float] = ...) -> SommerfeldRunup: ...

class FrequencyResponse(_Result):
    speed: float
    unit: str
    input: str
    frequencies: npt.NDArray[np.float64]
    dofs: list[str]
    H: npt.NDArray[np.complex128]
    amplitude: npt.NDArray[np.float64]
    phase: npt.NDArray[np.float64]  # degrees
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...
    def plot_polar(self, path: Optional[Path] = ..., axes: Any = ...) -> Any: ...

def frf(model: Model, speed: float, input: str, frequencies: Optional[npt.ArrayLike] = ..., *, dofs: Optional[Sequence[str]] = ...,
        probes: Optional[Sequence[tuple[int, float]]] = ..., unit: Optional[str] = ...,
        solver: Optional[str] = ...) -> FrequencyResponse: ...

class StaticDeflection(_Result):
    nodes: dict[str, Any]
    sections: dict[str, Any]
    reactions: dict[str, Any]
    weight: float
    backward_error: float
    balance_error: float
    condition: float
    error_bound: float
    def to_pandas(self, table: str = ...) -> Any: ...

def static(model: Scene, *, gravity: float = ..., loads: Optional[Sequence[Mapping[str, float]]] = ...) -> StaticDeflection: ...

class CriticalSpeedMap(_Result):
    def __init__(self, d: dict[str, Any], unit: str) -> None: ...
    unit: str
    stiffness: npt.NDArray[np.float64]
    points: dict[str, Any]
    rigid: dict[str, Any]
    bearings: list[dict[str, Any]]
    max_backward_error: float
    def to_pandas(self) -> Any: ...

def critical_speed_map(model: Scene, *, stiffness: Optional[Sequence[float]] = ..., modes: int = ...,
                       unit: Optional[str] = ...) -> CriticalSpeedMap: ...

class Level1(_Result):
    def __init__(self, d: dict[str, Any]) -> None: ...
    unit: str
    q: npt.NDArray[np.float64]
    log_decrement: npt.NDArray[np.float64]
    log_decrement_bound: npt.NDArray[np.float64]
    frequency: npt.NDArray[np.float64]
    whirl: list[str]
    bearing_set: str
    bearing_sets: list[dict[str, Any]]
    passed: list[dict[str, Any]]
    qa: float
    stage_qa: list[float]
    q0: Optional[float]
    q0_bound: float
    log_decrement_at_qa: float
    log_decrement_at_zero: float
    mcs: float
    layout: str
    station_nodes: list[int]
    station_shares: list[float]
    station_z: list[float]
    rigid_critical: Optional[float]
    csr: Optional[float]
    region_boundary: Optional[float]
    level2_required: bool
    reasons: list[str]
    solves: int
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

def level1(model: Scene, *, unit: Optional[str] = ..., machine: Optional[str] = ..., mcs: Optional[float] = ...,
           operating_speed: Optional[float] = ..., qa: Optional[float] = ..., station: Optional[float] = ...,
           gas_density: Optional[float] = ..., q_ratio: Optional[float] = ..., intervals: int = ...,
           method: str = ...) -> Level1: ...

class ApiUnbalance(_Result):
    def __init__(self, d: dict[str, Any]) -> None: ...
    unit: str
    verdict: str
    reasons: list[str]
    mcs: float
    min_speed: float
    trip_speed: float
    search_to: float
    locations: list[str]
    probe: list[bool]
    nodes: list[int]
    z: npt.NDArray[np.float64]
    clearance: list[float]
    speeds: npt.NDArray[np.float64]
    cases: list[dict[str, Any]]
    solves: int
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

def api_unbalance(model: Scene, *, unit: Optional[str] = ..., mcs: Optional[float] = ...,
                  min_speed: Optional[float] = ..., trip_speed: Optional[float] = ...,
                  speeds: int = ...) -> ApiUnbalance: ...

class MeshConvergence(_Result):
    def __init__(self, d: dict[str, Any]) -> None: ...
    unit: str
    tolerance: float
    top_speed: float
    factors: list[int]
    elements: list[int]
    dofs: list[int]
    quantities: list[dict[str, Any]]
    chosen: int
    section_elements: list[int]
    notes: list[str]
    warnings: list[str]
    def to_pandas(self) -> Any: ...

def mesh_convergence(model: Scene, *, unit: Optional[str] = ..., tolerance: float = ...,
                     levels: int = ...) -> MeshConvergence: ...

class Report:
    html: str
    title: str
    unit: str
    version: str
    generated: str
    sections: list[dict[str, Any]]
    inputs: list[tuple[str, str]]
    failed: list[str]
    def __init__(self, d: dict[str, Any], inputs: Any) -> None: ...
    def write(self, path: Any) -> None: ...

def report(model: Scene, path: Any = ..., *, unit: Optional[str] = ..., mode_shapes: int = ...) -> Report: ...

class ModelSummary(_Result): ...

def summary(scene: Scene) -> ModelSummary: ...

class TransientResponse(_Result):
    unit: str
    t: npt.NDArray[np.float64]
    speed: npt.NDArray[np.float64]
    z: npt.NDArray[np.float64]
    dofs: list[str]
    dt: float
    notes: list[str]
    stats: dict[str, Any]
    envelope: dict[str, npt.NDArray[Any]]
    def to_pandas(self, table: str = ...) -> Any: ...
    def waterfall(self, dof: Union[str, int] = ..., windows: int = ..., frequencies: int = ...) -> dict[str, Any]: ...
    def plot_waterfall(self, path: Optional[Path] = ..., axes: Any = ...) -> Any: ...
def transient(model: Model, speed: Optional[float] = ..., *, run_up: Optional[tuple[float, float]] = ...,
              acceleration: Optional[float] = ..., duration: Optional[float] = ..., dt: Optional[float] = ...,
              dofs: Optional[Sequence[str]] = ..., node: Optional[int] = ..., unit: Optional[str] = ..., start: str = ...,
              max_steps: int = ..., solver: Optional[str] = ..., windows: int = ...) -> TransientResponse: ...
