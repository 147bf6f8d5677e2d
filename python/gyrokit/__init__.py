"""gyrokit: Campbell diagrams, critical speeds and stability of gyroscopic systems.

Load a scene or build a system from NumPy or SciPy matrices, then call the
analyses; results are small objects holding NumPy arrays, with ``to_pandas()``
(when pandas is installed) and ``plot()`` (when matplotlib is installed).
Errors are ``gyrokit.Error`` (``InputError`` for bad input, ``SolverError``
when no verified answer was found). See docs/python.md.
"""
from __future__ import annotations

import functools as _functools
import inspect as _inspect
import os as _os
import typing as _typing
import warnings as _warnings

import numpy as _np

from ._core import Error, InputError, Scene, SolverError, System, __version__
from ._core import Bearing, Disk, Material, Pedestal, Rotor, Section, Support, coupling, materials
from ._core import FluidRotorParameters, GyrostatParameters
from . import _core
from . import _defaults as _D
from ._results import Result as _Result, Table, draw, load_tables
from ._results import UNITS as _UNITS, factor as _factor
from ._transient import TransientResponse, transient

# For annotations in scripts: what the analyses take as a model and as a file name.
Model = _typing.Union[System, Scene]
Path = _typing.Union[str, _os.PathLike[str]]

__all__ = ["Error", "InputError", "SolverError", "System", "Scene", "load_scene", "eig", "campbell",
           "critical_speeds", "stability", "screen", "EigResult", "CampbellResult", "CriticalSpeeds",
           "StabilityChanges", "ScreenResult", "pervasive", "response", "PervasiveLosses", "Response", "gyrostat",
           "fe_rotor", "fluid_rotor", "matrices_scene", "balancer", "sommerfeld", "BalancerStates", "BalancerRun", "Sommerfeld", "SommerfeldRunup",
           "modes", "ModeShapes", "Rotor", "Section", "Material", "materials", "Disk", "Bearing", "Support", "Pedestal", "coupling",
           "rotor_scene", "static", "StaticDeflection", "critical_speed_map", "CriticalSpeedMap", "frf",
           "FrequencyResponse", "Table", "load_tables", "draw", "summary", "ModelSummary", "transient",
           "TransientResponse", "defaults", "fluid", "FluidResult", "GyrostatParameters", "FluidRotorParameters",
           "level1", "Level1", "api_unbalance", "ApiUnbalance", "mesh_convergence", "report", "Report",
           "MeshConvergence"]


def defaults() -> list:
    """The defaults of every call and command, as `gyrokit defaults` prints them (docs/defaults.md): a list of
    dicts name, value (as written in a call; "" where the default is a rule), meaning, option (the CLI's),
    keyword (Python's), command and function (where the row applies to one command and call only; "": to
    every one with that option or keyword)."""
    return [dict(row) for row in _D.TABLE]


def load_scene(path, overrides=None, motion=None) -> Scene:
    """Reads a scene file (TOML); `overrides` maps "TABLE.KEY" to numbers (e.g. {"model.c_G": 400.0}).
    `motion` ("lateral", "all", "axial" or "torsional") builds that DOF set of an fe_rotor model in place
    of the scene's motion / dofs_per_node (e.g. a torsional analysis of a rotor described once)."""
    return _core.load_scene(str(path), dict(overrides or {}), motion or "")


def _request(**given):
    """The call's keywords as the library's request (resolve_request): None is "not given", so that the scene's
    [speeds] and [analysis] and then the table of defaults decide, as for the CLI. Speeds as a flat list."""
    speeds = given.get("speeds")
    if speeds is not None:
        try:
            given["speeds"] = _np.asarray(speeds, dtype=float).ravel().tolist()
        except (TypeError, ValueError):
            raise InputError(f"speeds = {speeds!r}: allowed: numbers (a list or an array)") from None
    return given


def _log_dec(lam):
    """-2 pi Re / Im of each eigenvalue, as the CLI's log_dec: a real eigenvalue (no oscillation) gives
    +inf where it decays, -inf where it grows, 0 at zero; NaN where a branch has no point."""
    lam = _np.asarray(lam, dtype=complex)
    real = _np.isfinite(lam) & (lam.imag == 0)
    not_oscillating = _np.where(lam.real < 0, _np.inf, _np.where(lam.real > 0, -_np.inf, 0.0))
    with _np.errstate(divide="ignore", invalid="ignore"):
        return _np.where(lam.imag > 0, -2 * _np.pi * lam.real / _np.where(lam.imag > 0, lam.imag, 1.0),
                         _np.where(real, not_oscillating, _np.nan))


def _zeta(lam):
    lam = _np.asarray(lam)
    return _np.where(_np.abs(lam) > 0, -lam.real / _np.maximum(_np.abs(lam), 1e-300), 0.0)


class EigResult(_Result):
    """Eigenvalues at one speed, one per conjugate pair (Im >= 0) as the CLI prints, by frequency. `speed` and
    `frequencies` in `unit`; eigenvalues (and their real parts) in 1/s, as the CLI's re_1_s, im_rad_s."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        self.speed = d["speed"] * f
        self.eigenvalues = d["eigenvalues"]
        self.frequencies = self.eigenvalues.imag * f
        self.damping_ratios = _zeta(self.eigenvalues)
        self.log_decrements = _log_dec(self.eigenvalues)
        self.backward_errors = d["backward_errors"]
        self.error_bounds = d["error_bounds"]
        self.whirl = list(d["whirl"])
        self.stability = list(d["stability"])
        self.vectors = d["vectors"]
        self.rigid_body = d["rigid_body"]
        self.method = d["method"]
        self.notes = list(d["notes"])
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"real": self.eigenvalues.real, "frequency": self.frequencies,
                            "damping_ratio": self.damping_ratios, "log_dec": self.log_decrements,
                            "whirl": self.whirl, "stability": self.stability,
                            "backward_error": self.backward_errors, "error_bound": self.error_bounds})


class CampbellResult(_Result):
    """Tracked modes over speed: eigenvalues[i, b] of branch b at speeds[i] (NaN where b has no point).
    `speeds` and `frequencies` in `unit`; eigenvalues in 1/s; damping_ratios and log_decrements alike."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        self.speeds = d["speeds"] * f
        self.eigenvalues = d["eigenvalues"]
        self.frequencies = self.eigenvalues.imag * f
        self.damping_ratios = _np.where(_np.isnan(self.eigenvalues.real), _np.nan, _zeta(self.eigenvalues))
        self.log_decrements = _log_dec(self.eigenvalues)
        self.backward_errors = d["backward_errors"]
        self.whirl = d["whirl"]
        self.branches = d["branches"]
        # The modes up to f_cut beyond the K shown, judged as the shown ones (their ids K + 1 on).
        self.judged_branches = d["judged_branches"]
        self.judged_eigenvalues = d["judged_eigenvalues"]
        self.inserted_speeds = d["inserted_speeds"]
        self.ambiguous_steps = d["ambiguous_steps"]
        self.max_backward_error = d["max_backward_error"]
        self.rigid_body = d["rigid_body"]
        self.notes = list(d["notes"])
        self.warnings = list(d["warnings"])
        self._take_reports(d)

    def to_pandas(self):
        """One row per speed and branch: the CLI's campbell table."""
        rows = {"speed": [], "branch": [], "frequency": [], "real": [], "whirl": [], "damping_ratio": [],
                "log_dec": [], "backward_error": []}
        for i, w in enumerate(self.speeds):
            for b, branch in enumerate(self.branches):
                lam = self.eigenvalues[i, b]
                if _np.isnan(lam.real):
                    continue
                rows["speed"].append(w)
                rows["branch"].append(int(branch))
                rows["frequency"].append(self.frequencies[i, b])
                rows["real"].append(lam.real)
                rows["whirl"].append(self.whirl[i][b])
                rows["damping_ratio"].append(self.damping_ratios[i, b])
                rows["log_dec"].append(self.log_decrements[i, b])
                rows["backward_error"].append(self.backward_errors[i, b])
        return self._frame(rows)


class CriticalSpeeds(_Result):
    """Crossings of tracked branches with the lines k * speed, refined by root finding, each with its
    API 684 amplification factor (half-power on the unbalance response, else 1/(2 zeta)); api684_critical
    is False for a heavily damped crossing (amplification factor < 2.5). Speeds in `unit`."""

    def __init__(self, d):
        self.unit = d["unit"]
        self.speeds = d["speeds"] * _factor(self.unit)
        self.bounds = d["bounds"] * _factor(self.unit)   # |speed - exact crossing| <= bound
        self.harmonic = d["harmonic"]
        self.branch = d["branch"]
        self.whirl = list(d["whirl"])
        self.damping_ratio = d["damping_ratio"]
        z = _np.asarray(self.damping_ratio, dtype=float)
        with _np.errstate(invalid="ignore", divide="ignore"):
            self.log_dec = _np.where(z < 1, 2 * _np.pi * z / _np.sqrt(_np.maximum(1 - z * z, 0.0)), _np.nan)
        self.amplification = d["amplification"]
        self.af_method = list(d["af_method"])
        self.af_dof = list(d["af_dof"])     # the DOF whose response gave a half-power AF ("" for 1/(2 zeta))
        self.af_note = list(d["af_note"])   # why 1/(2 zeta) where the half-power method did not apply
        self.notes = list(d["notes"])
        self.warnings = list(d["warnings"])
        self.api684_critical = d["api684_critical"]
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"speed": self.speeds, "bound": self.bounds, "branch": self.branch, "whirl": self.whirl,
                            "harmonic": self.harmonic, "damping_ratio": self.damping_ratio, "log_dec": self.log_dec,
                            "amplification": self.amplification, "af_method": self.af_method,
                            "af_dof": self.af_dof, "af_note": self.af_note,
                            "api684_critical": self.api684_critical})


class StabilityChanges(_Result):
    """Speeds where a branch becomes unstable (or stable again), refined by root finding;
    bounds: |speed - exact threshold| <= bound. Both in `unit`."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        self.speeds = d["speeds"] * f
        self.bounds = d["bounds"] * f
        self.branch = d["branch"]
        self.becomes_unstable = d["becomes_unstable"]
        self.notes = list(d["notes"])
        self.warnings = list(d["warnings"])
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"speed": self.speeds, "bound": self.bounds, "branch": self.branch,
                            "becomes_unstable": self.becomes_unstable})


def eig(model, speed, *, solver=None, modes=None, target=None, target_order=None, method=_D.METHOD,
        lanczos=_D.LANCZOS, unit=None) -> EigResult:
    """Eigenvalues at one speed (in `unit`: rad/s, Hz, rpm; default the scene's [speeds] units, else rad/s).
    solver: "auto" | "dense" | "sparse"; modes: K the K lowest (sparse: nearest the target), 0 = all."""
    return EigResult(_core.eig(model, float(speed), _request(solver=solver, modes=modes, target=target,
                                                              target_order=target_order, method=method,
                                                              lanczos=lanczos, unit=unit)))


class ModeShapes(_Result):
    """Mode shapes at one speed: shapes[:, j] is mode numbers[j]'s eigenvector scaled to 1 at its
    reference entry (the largest in metres); orbits: one entry per mode and whirl pair (semi-axes
    major/minor in the pair's unit, angle and phase in rad, whirl), as `gyrokit modes` prints.
    `speed` and `frequencies` in `unit`."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        dof_names = d["dof_names"]
        self.speed = d["speed"] * f
        self.eigenvalues = d["eigenvalues"]
        self.frequencies = self.eigenvalues.imag * f
        self.damping_ratios = _zeta(self.eigenvalues)
        self.log_decrements = _log_dec(self.eigenvalues)
        self.shapes = d["shapes"]
        self.numbers = list(d["numbers"])
        self.reference = [dof_names[i] for i in d["reference"]]
        self.whirl = list(d["whirl"])
        self.dof_names = list(dof_names)
        self.orbits = {k: (list(v) if k in ("pair", "unit", "whirl") else _np.asarray(v))
                       for k, v in d["orbits"].items()}
        self.notes = list(d["notes"])
        self._take_reports(d)
        self._shape_set = d["shape_set"]

    def to_pandas(self):
        """One row per mode and whirl pair: the orbit table."""
        return self._frame(self.orbits)

    def _numbers(self, mode, one=False):
        """The mode numbers asked for: one whole number of `numbers`, or (unless `one`) a non-empty list."""
        import numbers
        allowed = f"allowed: {'one of ' if one else ''}{', '.join(map(str, self.numbers))} (the modes computed)"
        single = isinstance(mode, (numbers.Number, _np.generic, str)) or _np.ndim(mode) == 0
        chosen = [mode] if single else list(mode)
        if not chosen or (one and len(chosen) != 1):
            raise InputError(f"mode = {mode!r}; {allowed}")
        for k in chosen:
            whole = isinstance(k, numbers.Integral) and not isinstance(k, (bool, _np.bool_))
            if not whole or int(k) not in self.numbers:
                raise InputError(f"mode = {k!r}; {allowed}")
        return [int(k) for k in chosen]

    def plot(self, path=None, axes=None, mode=None):
        """The CLI's figure (`gyrokit modes --plot`) of every mode, or of `mode` alone (a number of `numbers`,
        or a list of them): into `path` (.png or .svg, gnuplot) or with matplotlib (returns its Figure)."""
        figure = self._figure if mode is None else self._shape_set.figure(self._numbers(mode))
        return self._draw_figure(figure, path, axes)

    def plot_orbits(self, mode=None, ax=None):
        """The orbits of one mode (a number of `numbers`; default the first) in 3D: each whirl pair's ellipse
        in metres at its axial position z, the shaft's axis drawn through them (matplotlib). x and y share one
        scale, so an ellipse is drawn true to shape (a nearly planar mode flat, not round). Returns the Figure."""
        plt = self._pyplot()
        number = self.numbers[0] if mode is None else self._numbers(mode, one=True)[0]
        o = self.orbits
        rows = [i for i in range(len(o["mode"])) if o["mode"][i] == number and o["unit"][i] == "m"]
        if ax is None:
            ax = plt.figure().add_subplot(projection="3d")
        t = _np.linspace(0.0, 2 * _np.pi, 73)
        zs, reach = [], 0.0
        for i in rows:
            a, b, th, ph = o["major"][i], o["minor"][i], o["angle"][i], o["phase"][i]
            u, v = a * _np.cos(t + ph), b * _np.sin(t + ph)
            ax.plot(_np.full_like(t, o["z"][i]), u * _np.cos(th) - v * _np.sin(th), u * _np.sin(th) + v * _np.cos(th),
                    color="C0" if o["whirl"][i] == "forward" else "C3", linewidth=0.8)
            zs.append(o["z"][i])
            reach = max(reach, abs(a))
        if zs:
            ax.plot([min(zs), max(zs)], [0, 0], [0, 0], "k-.", linewidth=0.6)
        # One scale for x and y: the same limits and the same box side.
        reach = 1.05 * reach if reach > 0 else 1.0
        ax.set_ylim(-reach, reach)
        ax.set_zlim(-reach, reach)
        ax.set_box_aspect((2.0, 1.0, 1.0))
        j = self.numbers.index(number)
        ax.set_title(f"mode {number}: {self.frequencies[j]:.6g} {self.unit} ({self.whirl[j]})")
        ax.set_xlabel("z [m]")
        ax.set_ylabel("x")
        ax.set_zlabel("y")
        return ax.figure


def modes(model, speed, *, solver=None, modes=None, target=None, target_order=None, method=_D.METHOD,
          lanczos=_D.LANCZOS, unit=None) -> ModeShapes:
    """Mode shapes at one speed (in `unit`; default the scene's [speeds] units, else rad/s): the `modes` lowest
    (None: the scene's, 0: all)."""
    return ModeShapes(_core.mode_shapes(model, float(speed), _request(solver=solver, modes=modes, target=target,
                                                                       target_order=target_order, method=method,
                                                                       lanczos=lanczos, unit=unit)))


def campbell(model, speeds=None, *, harmonics=None, solver=None, modes=None, target=None, target_order=None,
             method=_D.METHOD, lanczos=_D.LANCZOS, jobs=_D.JOBS, unit=None, f_cut=None) -> CampbellResult:
    """Campbell diagram over `speeds` (in `unit`; default: the scene's [speeds]); jobs threads (0 = all cores).
    modes None (and no scene value): the modes in the band the speeds and harmonics excite; modes K: the K
    lowest branches shown, every mode up to f_cut (in `unit`; default: the scene's, else 1.5 times the
    highest excitation) tracked and judged."""
    return CampbellResult(_core.campbell(model, _request(speeds=speeds, harmonics=harmonics, solver=solver, modes=modes,
                                                 target=target, target_order=target_order, method=method,
                                                 lanczos=lanczos, jobs=jobs, unit=unit, f_cut=f_cut)))


def critical_speeds(model, speeds=None, *, harmonics=None, solver=None, modes=None, target=None, target_order=None,
                    method=_D.METHOD, lanczos=_D.LANCZOS, jobs=_D.JOBS, unit=None, f_cut=None) -> CriticalSpeeds:
    """Critical speeds (in `unit`) where tracked branches cross k * speed, k in `harmonics` (default: the scene's,
    or 1); `speeds` in `unit` too."""
    return CriticalSpeeds(_core.critical_speeds(model, _request(speeds=speeds, harmonics=harmonics, solver=solver, modes=modes,
                                                 target=target, target_order=target_order, method=method,
                                                 lanczos=lanczos, jobs=jobs, unit=unit, f_cut=f_cut)))


def stability(model, speeds=None, *, harmonics=None, solver=None, modes=None, target=None, target_order=None,
               method=_D.METHOD, lanczos=_D.LANCZOS, jobs=_D.JOBS, unit=None, f_cut=None) -> StabilityChanges:
    """Speeds where a mode becomes unstable or stable again (Re lambda beyond its error bound), over the
    modes in range (modes None; with modes = K as well: K only says how many branches a diagram shows; 0:
    every mode); speeds in `unit`."""
    return StabilityChanges(_core.stability(model, _request(speeds=speeds, harmonics=harmonics, solver=solver, modes=modes,
                                                 target=target, target_order=target_order, method=method,
                                                 lanczos=lanczos, jobs=jobs, unit=unit, f_cut=f_cut)))


class ScreenResult(_Result):
    """Verdicts of a design study: one entry per design, in design order, as `gyrokit screen` writes them."""

    def __init__(self, d):
        self.columns = list(d["columns"])
        self._inputs = tuple(d.get("inputs", ()))   # the sweep, its base scene and the files it names
        rows = d["rows"]
        col = {name: [r[k] for r in rows] for k, name in enumerate(self.columns)}
        number = lambda cells: _np.array([float(c) if c != "" else _np.nan for c in cells], dtype=float)
        self.design = _np.array([int(c) for c in col["design"]], dtype=int)
        self.parameters = {p: number(col[p]) for p in d["parameters"]}
        self.quantities = {q: number(col[q]) for q in d["quantities"]}
        # Text columns (max_amplitude_probe); None where undefined.
        self.labels = {q: [c if c != "" else None for c in col[q]] for q in d.get("labels", [])}
        self.verdict = col["verdict"]
        self.failed = [c.split(";") if c else [] for c in col["failed"]]
        self.reason = col["reason"]
        self.unit = d["unit"]

    @property
    def passed(self):
        return _np.array([v == "pass" for v in self.verdict])

    def to_pandas(self):
        columns = {"design": self.design, **self.parameters, **self.quantities, **self.labels, "verdict": self.verdict,
                   "failed": [";".join(f) for f in self.failed], "reason": self.reason}
        return self._frame(columns)

    def plot(self, x=None, y=None, ax=None):
        """The designs over two parameters, coloured by verdict (the safe region); returns the Figure."""
        plt = self._pyplot()
        names = list(self.parameters)
        x = x or names[0]
        y = y or names[1]
        ax = ax or plt.subplots()[1]
        for verdict, colour in (("pass", "tab:green"), ("fail", "tab:red"), ("error", "tab:gray")):
            sel = _np.array([v == verdict for v in self.verdict])
            if sel.any():
                ax.scatter(self.parameters[x][sel], self.parameters[y][sel], c=colour, label=verdict, s=12)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.legend(fontsize="small")
        return ax.figure


def _screen_one(sweep, scene, names, values, index, number, attempt=0):
    """One design of a study (module level, so that process pools and Dask workers can run it). `attempt`
    only makes a retry a new task (Dask names a task by its arguments and would return the failed one)."""
    return _core.screen_design(sweep, scene, names, values, index, number)


def _one_design(values, i):
    """What a task needs of design i: its own values (given designs), or its index in the sweep file."""
    return ([values[i]], 0) if values is not None else (None, i)


def _screen_on(executor, sweep, scene, names, values, progress, retries):
    """The designs of a study on a concurrent.futures.Executor (a process pool, Dask's client.get_executor()):
    the rows of the threaded run. A task that failed where it ran (a worker killed, a lost connection) is
    submitted again, up to `retries` times; a design whose task still failed, or whose resubmission the
    executor refused (a broken process pool), is an error row naming the failure, never missing."""
    plan = _core.screen_plan(sweep, scene, names, values)
    total = plan["designs"]

    def submit(i):
        try:
            return executor.submit(_screen_one, sweep, scene, names, *_one_design(values, i), i, attempt=attempts[i])
        except Exception as e:   # an executor that no longer takes tasks: the design's failure
            return e

    rows, failure, attempts = [None] * total, [None] * total, [0] * total
    done = 0

    def collect(pending):
        nonlocal done
        for i, f in pending.items():
            attempts[i] += 1
            try:
                if isinstance(f, Exception):
                    raise f
                rows[i] = list(f.result())
            except (KeyboardInterrupt, InputError):
                for g in pending.values():
                    if not isinstance(g, Exception):
                        g.cancel()
                raise
            except Exception as e:   # the task, not the design, failed
                failure[i] = e
                continue
            done += 1
            if progress is not None:
                progress(done, total)

    collect({i: submit(i) for i in range(total)})
    # Retries one design at a time: a design that kills its worker takes no other design with it.
    for _ in range(retries):
        for i in [i for i in range(total) if rows[i] is None]:
            collect({i: submit(i)})
    for i in range(total):
        if rows[i] is None:
            e = failure[i]
            tries = "once" if attempts[i] == 1 else f"{attempts[i]} times"
            reason = f"not evaluated: the executor's task failed {tries} ({type(e).__name__}: {e})".replace("\n", " ")
            rows[i] = list(_core.screen_error_row(sweep, scene, names, *_one_design(values, i), i, reason))
            done += 1
            if progress is not None:
                progress(done, total)
    return ScreenResult(dict(columns=plan["columns"], rows=rows, parameters=plan["parameters"],
                             quantities=plan["quantities"], labels=plan["labels"], unit=plan["unit"]))


def screen(sweep, designs=None, *, scene=None, jobs=_D.JOBS, progress=None, executor=None, retries=1) -> ScreenResult:
    """A design study: the criteria of the sweep file `sweep` on its own designs, or on `designs`, a list of
    dicts {parameter: value} (e.g. {"model.c_G": 400.0}). `scene` (a Scene, e.g. from rotor_scene) is the
    base scene in place of the sweep's `scene` key: its parameter paths address the scene it writes
    (Scene.to_toml()). Designs run on `jobs` threads (0 = all cores) with the interpreter released, or,
    with `executor` (any concurrent.futures.Executor: a process pool, a Dask cluster's
    client.get_executor()), one task per design there, with the same rows; a task that fails where it ran
    is submitted again up to `retries` times (default 1), then gives its design an error row naming the
    failure. `progress(done, total)` is called after each design."""
    if scene is not None and not isinstance(scene, Scene):
        raise InputError(f"scene: expected a gyrokit.Scene, got {type(scene).__name__}")
    base = None if scene is None else (scene.to_toml(), scene.path)
    names = values = None
    if designs is not None:
        designs = list(designs)
        if not designs:
            raise InputError("designs: empty; allowed: a list of dicts {parameter: value}")
        names = list(designs[0])
        for i, d in enumerate(designs):
            if list(d) != names:
                raise InputError(f"designs[{i}]: parameters {sorted(d)} differ from those of designs[0] {sorted(names)}")
        values = [[float(d[n]) for n in names] for d in designs]
    if executor is not None:
        if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
            raise InputError(f"retries = {retries!r}: allowed: an integer >= 0")
        return _screen_on(executor, str(sweep), base, names, values, progress, retries)
    return ScreenResult(_core.screen(str(sweep), base, names, values, int(jobs), progress))


class FrequencyResponse(_Result):
    """Steady response to a unit harmonic force (or moment) at DOF `input`, the rotor spinning at `speed`:
    H[i, k] of DOF dofs[k] at frequencies[i] (complex, the output's unit per N or N m); amplitude, phase (deg).
    Speeds and frequencies in `unit`. plot(): the CLI's Bode plot; plot_polar(): its polar plot."""

    def __init__(self, d):
        self.unit, self.input = d["unit"], d["input"]
        f = _factor(self.unit)
        self.speed = d["speed"] * f
        self.frequencies = _np.asarray(d["frequencies"], dtype=float) * f
        self.dofs = list(d["names"])
        self.H = d["H"]
        self.notes, self.warnings = list(d["notes"]), list(d["warnings"])
        self.amplitude = _np.abs(self.H)
        self.phase = _np.degrees(_np.angle(self.H))
        self._take_reports(d)
        self._polar = d["polar_figure"]

    def to_pandas(self):
        return self._frame({"frequency": _np.repeat(self.frequencies, len(self.dofs)),
                            "dof": self.dofs * len(self.frequencies), "re": self.H.real.ravel(),
                            "im": self.H.imag.ravel(), "amplitude": self.amplitude.ravel(),
                            "phase": self.phase.ravel()})

    def plot_polar(self, path=None, axes=None):
        """The CLI's polar plot (--plot --polar): Im H against Re H, true to shape."""
        return self._draw_figure(self._polar, path, axes)


def _probes(probes):
    """[(node, angle in degrees), ...] for the core; InputError for anything else."""
    out = []
    for i, p in enumerate(probes or []):
        try:
            node, angle = p
            out.append((int(node), float(angle)))
            if int(node) != node:
                raise ValueError
        except (TypeError, ValueError):
            raise InputError(f"probes[{i}] = {p!r}; allowed: (node, angle in degrees from +x towards +y)") from None
    return out


def frf(model, speed, input, frequencies=None, *, dofs=None, probes=None, unit=None, solver=None) -> FrequencyResponse:
    """Frequency response functions of `model` (a System or Scene) spinning at `speed`: the response of `dofs`
    (names; default: the input itself, the driving point) or of displacement `probes` [(node, angle), ...] (x cos +
    y sin, degrees from +x towards +y; outputs named "NODE@ANGLE") to a unit harmonic force at DOF `input` (a name:
    "y12"; a moment: "tx12"), at `frequencies`; `speed` and `frequencies` in `unit` (rad/s, Hz, rpm; default the
    scene's [speeds] units, else rad/s). Dense or sparse LU by `solver` (auto: sparse above 200 DOFs). See docs/frf.md."""
    d = _core.frf(model, _request(unit=unit, solver=solver), str(input), float(speed),
                  None if frequencies is None else _np.asarray(frequencies, dtype=float).ravel().tolist(),
                  [str(x) for x in (dofs or [])], _probes(probes))
    return FrequencyResponse(d)


class StaticDeflection(_Result):
    """An FE rotor at standstill (docs/static.md): `nodes` (node, z, x, y, slope_x, slope_y), `sections` (each
    element's start and end: element, z, shear_x, moment_x, shear_y, moment_y; M = E I y'' vertical), `reactions`
    (reaction, node, z, fx, fy, mx, my: on the rotor), `weight` (N), and the checks `backward_error`,
    `balance_error`, `condition` and `error_bound` (of the deflections, relative). Lengths in m, forces in N, moments in N m."""

    def __init__(self, d):
        self.nodes = dict(d["nodes"])
        self.sections = dict(d["sections"])
        self.reactions = dict(d["reactions"])
        self.weight = d["weight"]
        self.backward_error = d["backward_error"]
        self.balance_error = d["balance_error"]
        self.condition = d["condition"]
        self.error_bound = d["error_bound"]
        self._take_reports(d)   # deflection, summary, reactions, internal_forces; plot(): deflection and moment

    def to_pandas(self, table="nodes"):
        """One table: "nodes", "sections" or "reactions"."""
        if table not in ("nodes", "sections", "reactions"):
            raise InputError(f"table = {table!r}; allowed: nodes, sections, reactions")
        return self._frame(getattr(self, table))


class CriticalSpeedMap(_Result):
    """Undamped critical speeds of an FE rotor against bearing stiffness (docs/critical_map.md): `points` and
    `rigid` (the rigid-support limit) as dicts of arrays (stiffness N/m, whirl, critical, speed, backward_error),
    `bearings` (each a dict name, stiffness, speed: the bearings' own curves), `stiffness`, `max_backward_error`;
    speeds in `unit`."""

    def __init__(self, d, unit):
        factor = _UNITS[unit]
        self.unit = unit
        self.stiffness = _np.asarray(d["stiffness"], dtype=float)
        self.points, self.rigid = dict(d["points"]), dict(d["rigid"])
        for t in (self.points, self.rigid):
            t["speed"] = t["speed"] * factor
        self.bearings = [dict(c, speed=_np.asarray(c["speed"]) * factor) for c in d["bearings"]]
        self.max_backward_error = d["max_backward_error"]
        self._take_reports(d)   # the map and the bearings' curves; plot(): the CLI's log-log map

    def to_pandas(self):
        rows = {k: list(self.points[k]) + list(self.rigid[k]) for k in self.points}
        return self._frame(rows)


def critical_speed_map(model, *, stiffness=None, modes=_D.MAP_MODES, unit=None) -> CriticalSpeedMap:
    """The undamped critical speed map of an FE rotor scene: the lowest `modes` critical speeds of each whirl at
    each bearing stiffness (N/m, increasing; default: 1e-2 to 1e3 times the shaft's 48 E I / L^3, 31 values),
    with the rigid-support limit and the bearings' own curves; speeds in `unit` (rad/s, Hz, rpm; default the
    scene's [speeds] units, else rad/s)."""
    if not isinstance(model, Scene):
        raise InputError(f"critical_speed_map: expected a gyrokit.Scene of an FE rotor, got {type(model).__name__}")
    unit = _core.resolve_unit(model, unit)
    return CriticalSpeedMap(_core.critical_speed_map(model, [float(k) for k in (stiffness or [])], int(modes), unit),
                            unit)


class Level1(_Result):
    """API 617 Level I stability of an FE rotor (docs/level1.md): the first forward mode's log decrement against
    the cross-coupled stiffness Q at the maximum continuous speed — arrays `q` (N/m), `log_decrement` (with
    `log_decrement_bound`), `frequency` (in `unit`), `whirl` — and `qa`, `stage_qa`, `q0` (None where the log
    decrement stays positive over the range) with `q0_bound`, `log_decrement_at_qa`, `log_decrement_at_zero`,
    where Q acts (`layout`, `station_nodes`, `station_shares`, `station_z` in m), `rigid_critical` (in `unit`),
    `csr`, `region_boundary`, the verdict `level2_required` and its `reasons`. Where a fluid film gives a
    clearance or viscosity band these are the worse end's (`bearing_set`: "minimum clearance" or "maximum
    clearance"; "" for the bearings as given), and `bearing_sets` holds each end's as a dict of the same keys.
    `passed`: the lower forward modes Q does not load (each a dict of frequency in `unit`, log_decrement and
    orbit_ratio, its orbit where Q acts over its largest), passed over but still judged."""

    def __init__(self, d):
        self.unit = d["unit"]
        self.bearing_set = d["bearing_set"]
        self.bearing_sets = [dict(s) for s in d["bearing_sets"]]
        self.passed = [dict(p) for p in d["passed"]]
        for k in ("q", "log_decrement", "log_decrement_bound", "frequency"):
            setattr(self, k, _np.asarray(d[k], dtype=float))
        self.whirl = list(d["whirl"])
        for k in ("qa", "q0", "q0_bound", "log_decrement_at_qa", "log_decrement_at_zero", "mcs", "layout",
                  "station_nodes", "station_shares", "station_z", "rigid_critical", "csr", "region_boundary",
                  "level2_required", "reasons", "solves", "notes", "warnings"):
            setattr(self, k, d[k])
        self.stage_qa = list(d["stage_qa"])
        self._take_reports(d)   # level1_summary, level1_stages, level1_curve; plot(): log decrement against Q

    def to_pandas(self):
        return self._frame({"q": self.q, "log_decrement": self.log_decrement,
                            "log_decrement_bound": self.log_decrement_bound, "frequency": self.frequency,
                            "whirl": self.whirl})


def level1(model, *, unit=None, machine=None, mcs=None, operating_speed=None, qa=None, station=None,
           gas_density=None, q_ratio=None, intervals=_D.LEVEL1_INTERVALS, method=_D.METHOD) -> Level1:
    """The API 617 Level I stability screen of an FE rotor scene: the scene's [api] machine data (mcs,
    stages or qa, gas_density, ...) with these keywords on top (speeds in `unit`: rad/s, Hz or rpm, default the
    scene's [speeds] units; `station` in the scene's length unit; `qa` in N/m replaces the stages')."""
    if not isinstance(model, Scene):
        raise InputError(f"level1: expected a gyrokit.Scene of an FE rotor, got {type(model).__name__}")
    num = (lambda v: None if v is None else float(v))
    return Level1(_core.level1(model, unit, machine, num(mcs), num(operating_speed), num(qa), num(station),
                               num(gas_density), num(q_ratio), int(intervals), method))


class ApiUnbalance(_Result):
    """The API 617 unbalance cases of an FE rotor (docs/api_unbalance.md): the `verdict` (pass, pass (scaled
    clearances), fail, not judged) with `reasons` where the whole study fails; the operating range `min_speed` to
    `mcs`, `trip_speed` and `search_to` (in `unit`); the `locations` (names, `probe` flags, `nodes`, `z` in m,
    diametral `clearance` in m, 0 for probes); the response `speeds` (in `unit`); and `cases`, one dict each:
    `layout`, `loads` (node, z, weight kg, weight_of, unbalance kg m, phase rad), `criticals` (speed, whirl,
    amplification, af_method, af_dof, af_note, side, margin and required in percent, met), per location
    `peak_to_peak`, `at`, `checked`, `limit` (m) and `ratio`, `curves` (peak-to-peak in m, speeds x locations),
    `a1`, `avl` (m), `scc`, `concern`, `margins_met`, `verdict`, `reasons`."""

    def __init__(self, d):
        for k in ("unit", "verdict", "reasons", "mcs", "min_speed", "trip_speed", "search_to", "locations", "probe",
                  "nodes", "clearance", "solves", "notes", "warnings"):
            setattr(self, k, d[k])
        self.z = _np.asarray(d["z"], dtype=float)
        self.speeds = _np.asarray(d["speeds"], dtype=float)
        self.cases = []
        for c in d["cases"]:
            c = dict(c)
            for k in ("peak_to_peak", "at", "checked", "limit", "ratio", "curves"):
                c[k] = _np.asarray(c[k], dtype=float)
            c["loads"] = [dict(x) for x in c["loads"]]
            c["criticals"] = [dict(x) for x in c["criticals"]]
            self.cases.append(c)
        self._take_reports(d)   # api_unbalance_summary, _cases, _loads, _margins, _amplitudes; plot(): the orbits

    def to_pandas(self):
        rows = []
        for i, c in enumerate(self.cases):
            for k, name in enumerate(self.locations):
                rows.append({"case": i + 1, "location": name, "probe": self.probe[k],
                             "peak_to_peak": c["peak_to_peak"][k], "at": c["at"][k], "checked": c["checked"][k],
                             "limit": c["limit"][k], "ratio": c["ratio"][k], "verdict": c["verdict"]})
        return self._frame(rows)


def api_unbalance(model, *, unit=None, mcs=None, min_speed=None, trip_speed=None,
                  speeds=_D.API_SPEEDS) -> ApiUnbalance:
    """The API 617 unbalance cases of an FE rotor scene: the scene's [api] speeds (mcs, min_speed, trip_speed)
    and [[api.clearance]] entries with these keywords on top (speeds in `unit`: rad/s, Hz or rpm, default the
    scene's [speeds] units); `speeds` grid speeds from 0 to the higher of the trip speed and 1.26 mcs."""
    if not isinstance(model, Scene):
        raise InputError(f"api_unbalance: expected a gyrokit.Scene of an FE rotor, got {type(model).__name__}")
    num = (lambda v: None if v is None else float(v))
    return ApiUnbalance(_core.api_unbalance(model, unit, num(mcs), num(min_speed), num(trip_speed), int(speeds)))


class MeshConvergence(_Result):
    """The mesh convergence of an FE rotor (docs/mesh_convergence.md): the meshes (`factors`, `elements`,
    `dofs`), `quantities` (dicts: `name`, `values` in `unit` per mesh, `change` per
    doubling, `converged`: the first mesh index from which every change is below `tolerance`, -1: none),
    `chosen` (the mesh index chosen, -1: not converged) and its `section_elements`."""

    def __init__(self, d):
        for k in ("unit", "tolerance", "top_speed", "factors", "elements", "dofs", "chosen", "section_elements",
                  "notes", "warnings"):
            setattr(self, k, d[k])
        self.quantities = [dict(q) for q in d["quantities"]]
        for q in self.quantities:
            q["values"] = _np.asarray(q["values"], dtype=float)
            q["change"] = _np.asarray(q["change"], dtype=float)
        self._take_reports(d)   # mesh_summary, mesh_quantities

    def to_pandas(self):
        rows = []
        for q in self.quantities:
            for i, f in enumerate(self.factors):
                rows.append({"quantity": q["name"], "factor": f, "elements": self.elements[i], "dofs": self.dofs[i],
                             "value": q["values"][i],
                             "change": q["change"][i] if i < len(q["change"]) else float("nan")})
        return self._frame(rows)


def mesh_convergence(model, *, unit=None, tolerance=_D.MESH_TOLERANCE, levels=_D.MESH_LEVELS) -> MeshConvergence:
    """The mesh convergence of an FE rotor scene: each section's elements doubled (up to `levels` meshes) until
    every critical speed over the scene's [speeds] and every frequency up to f_cut at the top speed changes by
    less than `tolerance` (a fraction: 1e-3 is 0.1 %) on doubling."""
    if not isinstance(model, Scene):
        raise InputError(f"mesh_convergence: expected a gyrokit.Scene of an FE rotor, got {type(model).__name__}")
    return MeshConvergence(_core.mesh_convergence(model, unit, float(tolerance), int(levels)))


class Report:
    """The HTML report of a scene (docs/report.md): `html` (the page), `title`, `unit`, `version`,
    `generated`, `sections` (one dict each: key, title, failed ("" where it ran), tables (their keys),
    figures (how many)), `failed` (the sections not computed, "title: reason"), `inputs` ((path,
    fingerprint) pairs); write(path) saves the page, never over one of the scene's files."""

    def __init__(self, d, inputs):
        for k in ("html", "title", "unit", "version", "generated"):
            setattr(self, k, d[k])
        self.sections = [dict(s) for s in d["sections"]]
        self.inputs = [tuple(i) for i in d["inputs"]]
        self.failed = [f"{s['title']}: {s['failed']}" for s in self.sections if s["failed"]]
        self._scene_inputs = list(inputs)

    def write(self, path):
        _core.write_report(self.html, str(path), self._scene_inputs)

    def _repr_html_(self):
        # In a frame of its own: the page's styles and ids stay out of the notebook's.
        import html as _html
        return (f'<iframe srcdoc="{_html.escape(self.html, quote=True)}" '
                'style="width:100%;height:640px;border:1px solid #ccc"></iframe>')

    def __repr__(self):
        return (f"<gyrokit.Report {self.title!r}: {len(self.sections)} sections"
                f"{', ' + str(len(self.failed)) + ' not computed' if self.failed else ''}>")


def report(model, path=None, *, unit=None, mode_shapes=_D.MODE_SHAPES) -> Report:
    """The analyses a scene supports as one self-contained HTML page (the CLI's `gyrokit report`): the model,
    the undamped critical speed map, the Campbell diagram and critical speeds, the mode shapes at the critical
    speeds, stability, the API 617 unbalance cases and Level I (with [api] data). `path`: also written there."""
    if not isinstance(model, Scene):
        raise InputError(f"report: expected a gyrokit.Scene, got {type(model).__name__}")
    r = Report(_core.report(model, unit, int(mode_shapes)), model.inputs)
    if path is not None:
        r.write(path)
    return r


def static(model, *, gravity=_D.GRAVITY, loads=None) -> StaticDeflection:
    """An FE rotor scene at standstill under gravity (m/s^2 along -y) and point loads, a list of dicts
    {"node": n, "fx": .., "fy": .., "mx": .., "my": ..} (N, N m; missing ones 0). Speed-dependent bearings hold
    their nodes rigidly; constant bearings act as springs (docs/static.md)."""
    if not isinstance(model, Scene):
        raise InputError(f"static: expected a gyrokit.Scene of an FE rotor, got {type(model).__name__}")
    rows = []
    for i, l in enumerate(loads or []):
        unknown = sorted(set(l) - {"node", "fx", "fy", "mx", "my"})
        if unknown or "node" not in l:
            raise InputError(f"loads[{i}]: {unknown[0] if unknown else 'node'!r}: allowed keys node (required), fx, fy, "
                             "mx, my")
        if int(l["node"]) != l["node"]:
            raise InputError(f"loads[{i}]: node = {l['node']!r}; allowed: a node number")
        rows.append([float(l["node"])] + [float(l.get(k, 0.0)) for k in ("fx", "fy", "mx", "my")])
    return StaticDeflection(_core.static(model, float(gravity), rows))


class ModelSummary(_Result):
    """What a model is, as `gyrokit model` prints it: `tables` (quantity, value, unit: DOFs, mass, nodes,
    damping, bearings, ...); plot(): the drawing of an FE rotor (sections, disks, bearings, supports)."""

    def __init__(self, d):
        self._take_reports(d)

    def __str__(self):
        return str(self.tables[0])


def summary(scene) -> ModelSummary:
    """The model summary of a scene and, for an FE rotor, its drawing (ModelSummary)."""
    if not isinstance(scene, Scene):
        raise InputError(f"summary: expected a gyrokit.Scene, got {type(scene).__name__}")
    return ModelSummary(_core.model_summary(scene))


class PervasiveLosses(_Result):
    """Speeds where a damping set (a component alone, or "total") does not reach a mode (Hautus test);
    speeds and frequencies in `unit`. What was checked: `checked` (the sets), `checked_speeds`,
    `checked_modes` (modes of the undamped system, every one up to `f_cut`; None: every mode);
    `pervades`: the model has damping and no set loses a checked mode at a checked speed; `partial`: a
    sparse window that may miss modes up to f_cut (the notes say which)."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        self.checked = list(d["checked"])
        self.checked_speeds = int(d["checked_speeds"])
        self.checked_modes = int(d["checked_modes"])
        self.f_cut = None if d["f_cut"] is None else d["f_cut"] * f
        self.pervades = bool(d["pervades"])
        self.partial = bool(d["partial"])
        self.damping = list(d["damping"])
        self.speeds = d["speeds"] * f
        self.mode = d["mode"]
        self.frequency = d["frequency"] * f
        self.whirl = list(d["whirl"])
        self.residual = d["residual"]
        self.notes = list(d["notes"])
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"damping": self.damping, "speed": self.speeds, "mode": self.mode,
                            "frequency": self.frequency, "whirl": self.whirl, "residual": self.residual})


class Response(_Result):
    """Steady unbalance response: complex amplitudes Z[i, k] of DOF dofs[k] at speeds[i] (in `unit`); amplitude,
    phase (deg). plot(): the CLI's Bode plot (amplitude per unit, phase); plot_polar(): its polar plot."""

    def __init__(self, speeds, dofs, Z, d=None, unit="rad/s"):
        self.unit = unit
        self.notes = list(d["notes"]) if d else []
        self.warnings = list(d["warnings"]) if d else []
        self.speeds = _np.asarray(speeds, dtype=float) * _factor(unit)
        self.dofs = list(dofs)
        self.amplitudes = Z
        self.amplitude = _np.abs(Z)
        self.phase = _np.degrees(_np.angle(Z))   # degrees, as the CLI prints
        if d:
            self._take_reports(d)
            self._polar = d.get("polar_figure")

    def to_pandas(self):
        rows = {"speed": _np.repeat(self.speeds, len(self.dofs)), "dof": self.dofs * len(self.speeds),
                "amplitude": self.amplitude.ravel(), "phase": self.phase.ravel()}
        return self._frame(rows)

    def plot_polar(self, path=None, axes=None):
        """The CLI's polar plot (--plot --polar): Im Z against Re Z, one panel per unit, true to shape."""
        return self._draw_figure(getattr(self, "_polar", None), path, axes)


def pervasive(model, speeds=None, *, tolerance=_D.TOLERANCE, solver=None, modes=None, target=None, target_order=None,
              method=_D.METHOD, lanczos=_D.LANCZOS, jobs=_D.JOBS, unit=None) -> PervasiveLosses:
    """Hautus pervasive-damping check of each damping component alone and of the total damping; speeds in `unit`
    (default the scene's [speeds] units, else rad/s)."""
    return PervasiveLosses(_core.pervasive(model, float(tolerance),
                                           _request(speeds=speeds, solver=solver, modes=modes, target=target,
                                                    target_order=target_order, method=method, lanczos=lanczos,
                                                    jobs=jobs, unit=unit)))


def response(model, speeds=None, *, dofs=None, probes=None, solver=None, harmonics=None, modes=None,
             method=_D.METHOD, lanczos=_D.LANCZOS, jobs=_D.JOBS, unit=None, f_cut=None,
             stability_check=True, extrema=False, peaks=True) -> Response:
    """Unbalance response at `speeds` (in `unit`; default the scene's [speeds] units, else rad/s) of the named DOFs (default: all), by a dense or (solver "sparse";
    "auto" above 200 DOFs) sparse LU of the dynamic stiffness, with the CLI's tables (summary with the peaks refined
    between grid speeds, left out with peaks=False, which saves those searches; with `extrema` the peaks and
    antiresonances, as --extrema). As the CLI, the modes (`modes`, default those in range) are tracked
    over the range: each unstable range is a RuntimeWarning and in `warnings` (the response there is not a steady
    state); `stability_check=False` skips that tracking. `probes` [(node, angle), ...]: the readings of
    displacement probes (x cos + y sin, degrees from +x towards +y) instead of DOFs, named "NODE@ANGLE"."""
    if dofs is not None and probes is not None:
        raise InputError("dofs and probes: allowed: one of them")
    if dofs is not None and len(dofs) == 0:
        raise InputError("dofs: empty; allowed: DOF names, or None for every DOF")
    system = model.system if isinstance(model, Scene) else model
    names = system.dof_names
    missing = [d for d in (dofs or []) if d not in names]
    if missing:
        raise InputError(f"dofs: {missing[0]!r} is not a DOF of the model; allowed: names such as {names[0]!r}")
    cols = [] if dofs is None else [names.index(x) for x in dofs]
    d = _core.response(model, _request(speeds=speeds, harmonics=harmonics, solver=solver, modes=modes, method=method,
                                       lanczos=lanczos, jobs=jobs, unit=unit, f_cut=f_cut),
                       outputs=cols, probes=_probes(probes), stability_check=bool(stability_check),
                       extrema=bool(extrema), peaks=bool(peaks))
    for msg in d["warnings"]:
        _warnings.warn(msg, RuntimeWarning, stacklevel=2)
    return Response(d["speeds"], list(d["names"]), d["Z"], d, d["unit"])


# Models from keyword parameters, with the key names, checks and messages of scene files
# (docs/scene_format.md): the keywords become the [model] table of a scene.
def _toml_value(v, where):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, _np.integer)):
        return str(int(v))
    if isinstance(v, (float, _np.floating)):
        v = float(v)
        if not _np.isfinite(v):
            raise InputError(f"{where} = {v}: allowed: a finite number")
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple, _np.ndarray)):
        return "[" + ", ".join(_toml_value(x, where) for x in v) + "]"
    raise InputError(f"{where}: {type(v).__name__} is not a number, string or list")


def _model_scene(kind, keys, speeds=None, analysis=None, directory="."):
    lines = ["[model]", f'type = "{kind}"']
    tables = []
    for k, v in keys.items():
        if isinstance(v, (list, tuple)) and v and all(isinstance(x, dict) for x in v):
            tables.append((k, v))
        else:
            lines.append(f"{k} = {_toml_value(v, k)}")
    for k, items in tables:
        for item in items:
            lines.append(f"[[model.{k}]]")
            lines += [f"{kk} = {_toml_value(vv, k + '.' + kk)}" for kk, vv in item.items()]
    for name, table in (("speeds", speeds), ("analysis", analysis)):
        if table:
            lines.append(f"[{name}]")
            lines += [f"{k} = {_toml_value(v, name + '.' + k)}" for k, v in table.items()]
    return _core.parse_scene("\n".join(lines) + "\n", f"{kind}(...)", str(directory))


def gyrostat(parameters=None, *, title="", speeds=None, analysis=None, **keys) -> Scene:
    """The gyrostat with elastic shaft from a GyrostatParameters or its [model] keys: A_G, B_G, A_R, C_R, m, s,
    eps, c_G, c_T, c_R, d_G, d_T, d_R, shaft = "rigid", housing = "rigid" (docs/scene_format.md). speeds and
    analysis as rotor_scene's. The scene's `gyrostat` gives the parameters back."""
    p = _parameters(_core.GyrostatParameters, "gyrostat", parameters, keys)
    return _core.gyrostat_scene(p, str(title), *_settings(speeds, analysis))


def fe_rotor(*, speeds=None, analysis=None, directory=".", **keys) -> Scene:
    """A finite-element rotor from its [model] keys (docs/scene_format.md): material or E, poisson,
    density; dofs_per_node (4 or 6) or motion ("lateral", "all", "axial", "torsional"); length_unit
    ("m" or "mm"); shaft=[{length, elements, outer_diameter, inner_diameter, outer_diameter_end, ...} or
    {type: "coupling", length, k_lateral, k_bending, ..., c_torsion}],
    disk=[{z, mass, Id, Ip or outer_diameter, width, ...; unbalance}], bearing=[{z, k, c, kxx, ..., kzz}
    or {z, table} or {z, speeds: [...], k: [...], ...} or {z, type: "fluid_film", diameter, length,
    clearance, viscosity, load (N or "auto"), solution}], pedestal=[{z, mass, k, c}], support=[{z, type, axial,
    torsion}]; bearing tables are found relative to `directory`."""
    return _model_scene("fe_rotor", keys, speeds, analysis, directory)


def rotor_scene(rotor, *, title="", speeds=None, analysis=None) -> Scene:
    """A scene of an FE rotor built in Python (Rotor(sections=[Section(...)], disks=[Disk(...)], ...)), with
    speeds {"from": .., "to": .., "count": .., "units": ..} (units rad/s, Hz or rpm; default rad/s: the unit its
    results are given in unless a call names one) and analysis {"modes", "harmonics", "solver",
    "target", "target_order", "f_cut"} as a scene's [speeds] and [analysis]. Scene.to_toml() and Scene.write(path)
    give its scene file."""
    return _core.rotor_scene(rotor, str(title), *_settings(speeds, analysis))


def _settings(speeds, analysis):
    """A scene's [speeds] and [analysis] dicts as the core's arguments (span, modes, harmonics, solver, target,
    target_order, f_cut); the core checks their values."""
    speeds = dict(speeds or {})
    analysis = dict(analysis or {})
    for given, allowed, name in ((speeds, {"from", "to", "count", "units"}, "speeds"),
                                 (analysis, {"modes", "harmonics", "solver", "target", "target_order", "f_cut"},
                                  "analysis")):
        unknown = sorted(set(given) - allowed)
        if unknown:
            raise InputError(f"{name}: unknown key {unknown[0]!r}; allowed: {', '.join(sorted(allowed))}")
    span = None
    if speeds:
        missing = [k for k in ("from", "to") if k not in speeds]
        if missing:
            raise InputError(f"speeds: {missing[0]!r} is missing; required: from, to (in units), count (default 201)")
        span = (float(speeds["from"]), float(speeds["to"]), int(speeds.get("count", 201)), str(speeds.get("units", "rad/s")))
    harmonics = analysis.get("harmonics")
    return (span, analysis.get("modes"), None if harmonics is None else [int(h) for h in harmonics],
            str(analysis.get("solver", "auto")), analysis.get("target"), float(analysis.get("target_order", 0.0)),
            analysis.get("f_cut"))


def _parameters(kind, name, parameters, keys):
    """A model's parameters: the object given, or made from its [model] keys (not both)."""
    if parameters is None:
        return kind(**keys)
    if keys:
        raise InputError(f"{name}: parameters and keys {sorted(keys)} given together; allowed: one of them")
    if not isinstance(parameters, kind):
        raise InputError(f"{name}: expected a gyrokit.{kind.__name__}, got {type(parameters).__name__}")
    return parameters


def fluid_rotor(parameters=None, *, title="", speeds=None, analysis=None, **keys) -> Scene:
    """The liquid-filled rotor from a FluidRotorParameters or its [model] keys (docs/fluid_rotor.md): R, R0, a, l,
    rho, nu, c1, c2, c11, m0, I0, J0, e, modes or tolerance, jstar_terms. speeds and analysis as rotor_scene's.
    The scene's `fluid_rotor` gives the parameters back."""
    p = _parameters(_core.FluidRotorParameters, "fluid_rotor", parameters, keys)
    return _core.fluid_rotor_scene(p, str(title), *_settings(speeds, analysis))


def matrices_scene(directory, *, speeds=None, analysis=None, **keys) -> Scene:
    """A matrices model whose Matrix Market files (M, K, D, G, N, unbalance) lie in `directory`."""
    return _model_scene("matrices", keys, speeds, analysis, directory)


class FluidResult(_Result):
    """The liquid-filled rotor (docs/fluid_rotor.md), as `gyrokit fluid` prints it: `critical_speeds` by liquid
    model ("moving_undamped", "moving_damped", "rigid"; arrays in `unit`), `J_eq` and `J_eq_rigid` (kg m^2), or with
    a fill sweep `fills` (R0 in m) and `critical_speeds[model][k]` the speeds at fills[k]; `tables` (critical
    speeds, sloshing modes, liquid; or the sweep), `plot()` the sweep's figure; `notes`."""

    def __init__(self, d):
        self.unit = d["unit"]
        f = _factor(self.unit)
        self.fills = _np.asarray(d["fills"], dtype=float) if "fills" in d else None
        if self.fills is None:
            self.critical_speeds = {k: _np.asarray(v, dtype=float) * f for k, v in d["critical_speeds"].items()}
            self.J_eq, self.J_eq_rigid = d["J_eq"], d["J_eq_rigid"]
        else:
            self.critical_speeds = {k: [_np.asarray(x, dtype=float) * f for x in v]
                                    for k, v in d["critical_speeds"].items()}
        self.notes = list(d["notes"])
        self._take_reports(d)


def fluid(scene, *, fill=None, unit=None) -> FluidResult:
    """Critical speeds of a liquid-filled rotor scene (`[model] type = "fluid_rotor"`) with the liquid moving
    (undamped, damped) and frozen, and the sloshing coefficients; `fill` (free-surface radii R0 in m, 0 < R0 < R):
    the sweep over the fill level instead, as `gyrokit fluid --fill`. Speeds in `unit` (default the scene's
    [speeds] units, else rad/s)."""
    if not isinstance(scene, Scene):
        raise InputError(f"fluid: expected a gyrokit.Scene of a fluid_rotor model, got {type(scene).__name__}")
    return FluidResult(_core.fluid(scene, unit, None if fill is None else
                                   _np.asarray(fill, dtype=float).ravel().tolist()))


class BalancerStates(_Result):
    """Synchronous states of a two-roller auto-balancer and their stability per speed range (Tabellen 1-3)."""

    def __init__(self, d):
        self.state = list(d["state"])
        self.alpha_deg = [_np.degrees(a) for a in d["alpha"]]
        self.range = list(d["range"])
        self.range_from = d["range_from"]
        self.range_to = d["range_to"]
        self.stable = list(d["stable"])
        self.stable_eigen = list(d["stable_eigen"])
        self.max_real_eigenvalue = d["max_real_eigenvalue"]
        self.compensating = [bool(c) for c in d["compensating"]]
        # Per speed range: does a compensating state stay stable (as the CLI's first screen)?
        self.ranges = [dict(r) for r in d["ranges"]]
        self._take_reports(d)   # the CLI's tables: synchronous_states, balancing_ranges

    def to_pandas(self):
        return self._frame({"state": self.state, "range": self.range, "from_rad_s": self.range_from, "to_rad_s": self.range_to,
                            "stable": self.stable, "stable_eigen": self.stable_eigen,
                            "max_re_lambda_1_s": self.max_real_eigenvalue, "compensating": self.compensating})


class BalancerRun(_Result):
    """A run of the auto-balancer's equations of motion (`gyrokit balancer --simulate`): the histories `t` (s),
    `speed` (rad/s), `radius` (|r|, m) and `alpha` (the rollers' relative phases, rad, unwrapped), the final
    phases (rad) and speed (rad/s) and the residual vibration over the final window (m); `tables` (history,
    final_state; history with history=True) and `plot()` (the phase histories)."""

    def __init__(self, d):
        for key in ("t", "speed", "radius", "final_speed", "residual_rms", "residual_max"):
            setattr(self, key, d[key])
        self.alpha = list(d["alpha"])
        self.final_alpha = list(d["final_alpha"])
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"t_s": self.t, "speed_rad_s": self.speed, "radius_m": self.radius,
                            **{f"alpha{i + 1}_rad": a for i, a in enumerate(self.alpha)}})


class SommerfeldRunup(_Result):
    """A run-up through the full equations of motion (`gyrokit sommerfeld --runup`): the histories `t` (s),
    `nominal` and `rotor_speed` (rad/s), `amplitude` (|r|, m), the held rotor speed and amplitude and the final
    rotor speed; `tables` (runup_history, summary) and `plot()`."""

    def __init__(self, d):
        for key in ("t", "nominal", "rotor_speed", "amplitude", "held_rotor_speed", "held_amplitude",
                    "final_rotor_speed"):
            setattr(self, key, d[key])
        self._take_reports(d)

    def to_pandas(self):
        return self._frame({"t_s": self.t, "nominal_rad_s": self.nominal, "rotor_speed_rad_s": self.rotor_speed,
                            "amplitude_m": self.amplitude})


class Sommerfeld(_Result):
    """Sommerfeld effect of a rotor driven by a limited motor: limit speed estimate, folds, jump speeds (rad/s);
    `tables` (stationary_states, folds, summary) and `plot()` (the stationary speed curves)."""

    def __init__(self, d):
        self.limit_speed_estimate = d["limit_speed_estimate"]
        self.has_jump = d["has_jump"]
        self.folds = list(d["folds"])
        self.jump_up = d.get("jump_up")
        self.jump_up_rotor_speed = d.get("jump_up_rotor_speed")
        self.jump_down = d.get("jump_down")
        self.jump_down_rotor_speed = d.get("jump_down_rotor_speed")
        self._take_reports(d)

    def to_pandas(self):
        return self._frame(self.folds)


def balancer(scene, *, simulate=False, averaged=False, speed=None, duration=None, integrator=None, abs_tol=None,
             rel_tol=None, history=False):
    """The auto-balancer scene's synchronous states and their stability (as `gyrokit balancer`); `simulate`: a
    run of the equations of motion with the scene's [simulation] (`averaged`: the slow-phase equations; `speed`
    a prescribed speed in rad/s, `duration` s, the ODE `integrator` and tolerances override the scene), as
    `gyrokit balancer --simulate`; `history`: its tables hold the phase histories too (as --history)."""
    if history and not simulate:
        raise InputError("history: the phase histories of a run; allowed only with simulate=True")
    d = _core.balancer(str(scene), dict(simulate=bool(simulate), averaged=bool(averaged), speed=speed,
                                        duration=duration, integrator=integrator, abs_tol=abs_tol, rel_tol=rel_tol,
                                        history=bool(history)))
    return BalancerRun(d) if simulate else BalancerStates(d)


def sommerfeld(scene, *, speeds=None, runup=False, integrator=None, abs_tol=None, rel_tol=None, max_speed=None):
    """The Sommerfeld analysis of an auto-balancer scene with a motor (as `gyrokit sommerfeld`): the stationary
    curves over `speeds` (FROM, TO, N) nominal speeds in rad/s (default: the range the curves need); `runup`: the
    scene's [runup] through the full equations of motion (`max_speed` rad/s, the ODE `integrator` and tolerances
    override the scene), as `gyrokit sommerfeld --runup`."""
    d = _core.sommerfeld(str(scene), dict(runup=bool(runup), speeds=speeds, integrator=integrator, abs_tol=abs_tol,
                                          rel_tol=rel_tol, max_speed=max_speed))
    return SommerfeldRunup(d) if runup else Sommerfeld(d)


def _inputs_of(model):
    """The files an analysis of `model` read: a Scene's inputs, or a scene or sweep file's path."""
    if isinstance(model, Scene):
        return tuple(model.inputs)
    if isinstance(model, (str, _os.PathLike)):
        return (_os.path.abspath(str(model)),)
    return ()


def _keeping_inputs(analysis):
    """`analysis` whose result remembers the files it was computed from (Result._inputs): its first
    argument's (a Scene's inputs, or a scene or sweep file) and a `scene` keyword's."""
    signature = _inspect.signature(analysis)
    first = next(iter(signature.parameters))

    @_functools.wraps(analysis)
    def run(*args, **kwargs):
        result = analysis(*args, **kwargs)
        if isinstance(result, _Result):
            given = signature.bind_partial(*args, **kwargs).arguments
            inputs = _inputs_of(given.get(first)) + _inputs_of(given.get("scene") if first != "scene" else None)
            result._inputs = tuple(dict.fromkeys(tuple(result._inputs) + inputs))
        return result
    return run


# Every analysis of the module, so that no result is saved over what it was computed from.
for _name in ("eig", "modes", "campbell", "critical_speeds", "stability", "screen", "frf", "critical_speed_map",
              "static", "summary", "pervasive", "response", "balancer", "sommerfeld", "transient", "fluid", "level1",
              "api_unbalance", "mesh_convergence"):
    globals()[_name] = _keeping_inputs(globals()[_name])
del _name
