"""The luffing analysis of a scene (analysis: {type: luffing, ...}): the linkage's
kinematics, the energy-optimal law and its rivals, motor torque, load sway
(Loveikin, Palamarchuk, Khodnevych (2013); docs/luffing.md).

``analyse(model)`` returns a `LuffingResult`; it never prints.
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ...errors import ModelError

KEYS = {"type", "boom", "pivot", "tip", "alpha0_deg", "alphak_deg", "alpha0", "alphak",
        "reach0", "reachk", "t_k", "drive", "jib_tip", "load", "inertia",
        "rest_to_rest_tau"}
TABLE_LAWS = ("optimal", "linear", "cubic", "quintic", "cycloidal", "trapezoidal")
ALL_LAWS = TABLE_LAWS + ("optimal_paper", "rest_to_rest", "swing_free")
# the figures of each law (`Luffing.figures`; sweep outputs luffing.LAW.FIGURE)
FIGURES = ("T_mean_J", "T_ratio", "T_mean_paper_J", "peak_motor_torque_Nm", "peak_power_W",
           "speed_jump_rad_s", "motor_impulse_Nms", "max_sway_deg", "residual_sway_deg",
           "max_sway_linear_deg", "residual_sway_linear_deg",
           "residual_sway_linear_exact_deg", "max_sway_paper_eq9_deg", "T_load_mean_J",
           "peak_load_weight_torque_Nm", "max_alpha_deg", "min_alpha_deg")


@dataclass(frozen=True)
class Scene:
    """The checked keys of a luffing analysis."""

    boom: str
    pivot: str
    tip: str
    t_k: float
    drive: str
    jib_tip: str
    load_mass: float
    rope_length: float
    start: tuple            # ('alpha', rad) or ('reach', m)
    end: tuple
    inertia: str = "complete"
    rest_to_rest_tau: float = None


def read_scene(model, file=None):
    """Validate ``model.analysis`` (the loader leaves a luffing analysis unchecked)."""
    from ...model.load import _Reader
    file = file or model.scene_file or model.file
    r = _Reader(file)
    a = model.analysis or {}
    if a.get("type") != "luffing":
        raise ModelError("needs a scene with 'analysis: {type: luffing, boom: ..., pivot: "
                         "..., tip: ..., alpha0_deg: ..., alphak_deg: ..., t_k: ..., "
                         "drive: ..., jib_tip: ..., load: {mass: ..., rope_length: ...}}' "
                         "(docs/luffing.md)", file, "analysis")
    r.keys(a, "analysis", KEYS, required=("boom", "pivot", "tip", "t_k", "jib_tip", "load"))
    for k in ("boom", "pivot", "tip", "jib_tip"):
        r.name(a[k], f"analysis.{k}")
    if a["jib_tip"] not in model.node_index:
        r.fail("analysis.jib_tip", f"unknown node '{a['jib_tip']}'")
    drives = [d.name for d in model.linear_drives]
    if "drive" in a:
        drive = r.name(a["drive"], "analysis.drive")
        if drive not in drives:
            r.fail("analysis.drive", f"unknown linear drive '{drive}'; the model has: "
                   f"{', '.join(drives) or 'none (add linear_drives)'}")
    elif len(drives) == 1:
        drive = drives[0]
    else:
        r.fail("analysis.drive", "name the linear drive whose motor the energy is "
               f"reduced to (one of: {', '.join(drives) or 'none: add linear_drives'})")
    t_k = r.number(a["t_k"], "analysis.t_k", positive=True)
    load = a["load"]
    r.keys(load, "analysis.load", {"mass", "rope_length"}, required=("mass", "rope_length"))
    mass = r.number(load["mass"], "analysis.load.mass", nonneg=True)
    H = r.number(load["rope_length"], "analysis.load.rope_length", positive=True)
    ends = []
    for w in ("0", "k"):
        given = [k for k in (f"alpha{w}_deg", f"alpha{w}", f"reach{w}") if k in a]
        if len(given) != 1:
            r.fail("analysis", f"give exactly one of alpha{w}_deg, alpha{w} (rad) or "
                   f"reach{w} (m){'; found ' + ', '.join(given) if given else ''}")
        k = given[0]
        v = r.number(a[k], f"analysis.{k}")
        if k.endswith("_deg"):
            if not -180 < v < 180:
                r.fail(f"analysis.{k}", f"{v:g} deg is not a boom angle in (-180, 180)")
            ends.append(("alpha", math.radians(v), k))
        elif k.startswith("alpha"):
            if not -math.pi < v < math.pi:
                r.fail(f"analysis.{k}", f"{v:g} rad is not a boom angle in (-pi, pi)")
            ends.append(("alpha", v, k))
        else:
            ends.append(("reach", v, k))
    inertia = a.get("inertia", "complete")
    if inertia not in ("complete", "paper"):
        r.fail("analysis.inertia", f"{inertia!r}: use complete (links' translation "
               "included) or paper (eq. 3)")
    tau = r.number(a["rest_to_rest_tau"], "analysis.rest_to_rest_tau", positive=True) \
        if "rest_to_rest_tau" in a else t_k / 25
    if tau > t_k / 4:
        r.fail("analysis.rest_to_rest_tau", f"{tau:g} s is more than t_k/4; the "
               "practical law's acceleration time constant should be well below t_k")
    return Scene(a["boom"], a["pivot"], a["tip"], t_k, drive, a["jib_tip"], mass, H,
                 ends[0], ends[1], inertia, tau)


@dataclass
class LuffingResult:
    """Result of a luffing analysis (arrays over time are (n_laws, n_t))."""

    status: int
    message: str
    model_name: str
    scene: str
    alpha0: float                    # rad
    alphak: float
    t_k: float                       # s
    reach0: float                    # m (x of the jib tip)
    reachk: float
    load_mass: float
    rope_length: float
    inertia: str                     # the J the optimum minimises: complete | paper
    jib_tip_deviation: float         # m, max - min height of the tip over the range
    imbalance_moment: float          # N m, largest |dV/dalpha| of the links
    imbalance_motor_torque: float    # N m at the motor
    optimum: dict                    # figures of the optimum (T_mean, paper's, ...)
    table: dict                      # law -> figures
    law_names: tuple
    t: np.ndarray                    # (nt,) s
    alpha: np.ndarray                # (nl, nt) rad
    speed: np.ndarray                # rad/s
    motor_torque: np.ndarray         # N m
    kinetic_energy: np.ndarray       # J, complete
    sway: np.ndarray                 # rad, nonlinear with gravity
    sway_linear: np.ndarray          # rad
    alpha_grid: np.ndarray           # (ng,) over the luffing range
    tip_x: np.ndarray
    tip_z: np.ndarray
    J: np.ndarray                    # complete reduced inertia at the boom, kg m^2
    J_paper: np.ndarray              # eq. 3
    imbalance: np.ndarray            # dV/dalpha, N m
    motor_ratio: np.ndarray          # d(motor angle)/d alpha
    collocation: dict = field(default_factory=dict)
    sensitivity: dict = field(default_factory=dict)
    kinematics: dict = field(default_factory=dict)
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)

    def to_dict(self):
        """The JSON document of ``cranefe luff --json`` (docs/luffing.md)."""
        from .report import luffing_document
        return luffing_document(self)


class Luffing:
    """The linkage of a luffing scene with its reduced quantities (`Proxy`)."""

    def __init__(self, model, scene, file=None):
        from .energy import Proxy, Reduced
        from .kinematics import Linkage
        self.model, self.scene = model, scene
        file = file or model.scene_file or model.file
        self.linkage = Linkage(model, scene.boom, scene.pivot, scene.tip, file=file)
        drive = next(d for d in model.linear_drives if d.name == scene.drive)
        for n in drive.nodes:
            if self.linkage.carrier(n) is None:
                raise ModelError(f"node '{model.node_names[n]}' of linear drive "
                                 f"'{drive.name}' is neither ground nor on a body of the "
                                 "linkage", model.file, f"linear_drives.{drive.name}")
        tip = model.node_index[scene.jib_tip]
        if self.linkage.carrier(tip) is None:
            raise ModelError(f"node '{scene.jib_tip}' is not carried by a body of the "
                             "linkage", file, "analysis.jib_tip")
        self.reduced = Reduced(self.linkage, drive, tip)
        self.g = float(np.linalg.norm(model.gravity))
        self.alpha0 = self._angle(scene.start, file)
        self.alphak = self._angle(scene.end, file)
        if abs(self.alphak - self.alpha0) < 1e-9:
            raise ModelError("the start and end of the luffing coincide", file, "analysis")
        lo, hi = sorted((self.alpha0, self.alphak))
        margin = 0.05 * (hi - lo)
        from ...errors import AnalysisError
        for value, end in ((self.alpha0, scene.start), (self.alphak, scene.end)):
            try:
                self.linkage.cover(value, value)
            except AnalysisError as exc:
                raise ModelError(f"alpha = {np.degrees(value):.2f} deg is beyond the "
                                 f"linkage's range ({exc})", file,
                                 f"analysis.{end[2]}") from None
        for m in (margin, 0.0):                 # a margin for laws that overshoot
            try:
                self.linkage.cover(lo - m, hi + m)
                break
            except AnalysisError:
                if m == 0.0:
                    raise
        self.proxy = Proxy(self.reduced, lo - m, hi + m)
        self.lo, self.hi = lo, hi

    def _angle(self, end, file):
        """The boom angle of an end given as an angle or as a reach (x of the jib tip),
        searched outward from the model's geometry along the assembly branch."""
        kind, value, key = end
        if kind == "alpha":
            return value
        from ...errors import AnalysisError
        lk, red = self.linkage, self.reduced
        chunk = np.radians(10.0)
        for direction in (1, -1):
            a = lk.alpha_ref
            for _ in range(18):
                b = a + direction * chunk
                try:
                    lk.cover(min(a, b), max(a, b))
                except AnalysisError:
                    b = lk._A[-1] if direction > 0 else lk._A[0]
                grid = np.linspace(a, b, 41)
                x = red.evaluate(grid)["x"] - value
                hit = np.flatnonzero(x[:-1] * x[1:] <= 0)
                if len(hit):
                    lo, hi = grid[hit[0]], grid[hit[0] + 1]
                    c = 0.5 * (lo + hi)
                    for _ in range(50):                 # Newton inside the bracket
                        v = red.evaluate(np.array([c]))
                        step = (v["x"][0] - value) / v["dx"][0]
                        c = min(max(c - step, min(lo, hi)), max(lo, hi))
                        if abs(step) < 1e-15:
                            break
                    return float(c)
                if b == a or abs(b - a) < chunk * 0.999:
                    break
                a = b
        raise ModelError(f"reach {value:g} m is outside what the linkage can reach",
                         file, f"analysis.{key}")

    # ------------------------------------------------------------------ laws
    def optimal(self, which=None, extra_inertia=None, name="optimal"):
        """The exact optimum (quadrature) for the complete or the paper's inertia;
        extra_inertia: an array-callable added to J (e.g. a load carried rigidly)."""
        from .optimum import exact_law
        which = which or self.scene.inertia
        p, a0 = self.proxy, self.alpha0
        key = "sqrtJ" if which == "complete" else "sqrtJp"
        j = "J" if which == "complete" else "Jp"
        if extra_inertia is None:
            return exact_law(lambda a: p.antiderivative(key, a, a0), lambda a: p(key, a),
                             lambda a: p.f(a, which), a0, self.alphak, name)
        from numpy.polynomial import chebyshev as C
        x = np.cos(np.pi * (np.arange(129) + 0.5) / 129)
        al = p._from_unit(x)
        Jx, dJx = extra_inertia(al)
        cs = C.chebfit(x, np.sqrt(p(j, al) + Jx), 128)
        cf = C.chebfit(x, 0.5 * (p("d" + j, al) + dJx) / (p(j, al) + Jx), 128)
        ci = C.chebint(cs) * (p.hi - p.lo) / 2
        return exact_law(lambda a: C.chebval(p._to_unit(a), ci)
                         - C.chebval(p._to_unit(a0), ci),
                         lambda a: C.chebval(p._to_unit(a), cs),
                         lambda a: C.chebval(p._to_unit(a), cf), a0, self.alphak, name)

    def laws(self, names=ALL_LAWS):
        """The laws `names`, and always the optimum (every law's reference)."""
        from .laws import rest_to_rest_law, standard_law
        from .sway import swing_free_law
        sc = self.scene
        out = {"optimal": self.optimal()}
        for name in names:
            if name in TABLE_LAWS[1:]:
                out[name] = standard_law(name, self.alpha0, self.alphak)
            elif name == "optimal_paper":
                out[name] = self.optimal("paper" if sc.inertia == "complete"
                                         else "complete", name="optimal_paper")
            elif name == "rest_to_rest":
                out[name] = rest_to_rest_law(self.proxy, self.alpha0, self.alphak,
                                             sc.rest_to_rest_tau, sc.t_k, sc.inertia)
            elif name == "swing_free":
                out[name] = swing_free_law(self.proxy, self.alpha0, self.alphak, sc.t_k,
                                           sc.rope_length, self.g, out["optimal"],
                                           which=sc.inertia)
        return out

    def optimal_energy(self, optimal):
        """Mean kinetic energy of the optimum, T_mean = S^2 / (2 t_k^2) (eq. 16)."""
        return float(optimal.info["S"] ** 2 / (2 * self.scene.t_k**2))

    # ------------------------------------------------------------------ figures
    def mean_energy(self, law, key="J", nodes=64):
        """(1/t_k) int 1/2 J alpha'^2 dt by Gauss-Legendre on each smooth piece."""
        edges = [0.0, *law.info.get("breaks", []), 1.0]
        x, w = np.polynomial.legendre.leggauss(nodes)
        total = 0.0
        for a, b in zip(edges[:-1], edges[1:]):
            tau = 0.5 * (a + b) + 0.5 * (b - a) * x
            al, d1, _ = law.evaluate(tau)
            total += 0.5 * (b - a) * np.sum(w * 0.5 * self.proxy(key, al) * d1**2)
        return float(total / self.scene.t_k**2)

    def drive_terms(self, law, tau):
        """Motor torque (N m), power (W), links' generalised force Q (N m) and the load
        weight's torque at the motor (N m) at the instants tau."""
        p, tk = self.proxy, self.scene.t_k
        al, d1, d2 = law.evaluate(tau)
        ratio = self.reduced.ratio * p("ds", al)           # d(motor angle)/d alpha
        Q = (p("J", al) * d2 + 0.5 * p("dJ", al) * d1**2) / tk**2 + p("dV", al)
        load = self.scene.load_mass * self.g * p("dz", al)  # m g dz/dalpha
        return Q / ratio, Q * d1 / tk, Q, load / ratio

    def figures(self, law, T_opt, samples=801):
        """The comparison figures of one law, and its time series."""
        from .sway import TipMotion, residual_linear_exact, simulate
        sc, p = self.scene, self.proxy
        tau = np.linspace(0, 1, samples)
        al, d1, d2 = law.evaluate(tau)
        torque, power, _, load_torque = self.drive_terms(law, tau)
        T = 0.5 * p("J", al) * d1**2 / sc.t_k**2
        j = "J" if sc.inertia == "complete" else "Jp"
        T_mean = self.mean_energy(law, j)
        tip = TipMotion(law, p, sc.t_k)
        sway = {k: simulate(tip, sc.rope_length, self.g, k, samples=samples)
                for k in ("linear", "nonlinear", "paper")}
        nl = sway["nonlinear"]
        vx, vz = p("dx", al) * d1 / sc.t_k, p("dz", al) * d1 / sc.t_k
        H = sc.rope_length
        vl = np.hypot(vx + H * nl["dpsi"] * np.cos(nl["psi"]),
                      vz + H * nl["dpsi"] * np.sin(nl["psi"]))
        from scipy.integrate import trapezoid
        T_load = trapezoid(0.5 * sc.load_mass * vl**2, tau)
        ratio0 = self.reduced.ratio * p("ds", al[[0, -1]])
        jumps = np.abs(d1[[0, -1]]) / sc.t_k                  # speed jumps (rad/s)
        fig = {
            "T_mean_J": T_mean,
            "T_ratio": T_mean / T_opt,
            "T_mean_paper_J": self.mean_energy(law, "Jp"),
            "peak_motor_torque_Nm": float(np.abs(torque).max()),
            "peak_power_W": float(np.abs(power).max()),
            "speed_jump_rad_s": float(jumps.max()),
            "motor_impulse_Nms": float(np.max(p("J", al[[0, -1]]) * jumps / np.abs(ratio0))),
            "max_sway_deg": math.degrees(nl["max"]),
            "residual_sway_deg": math.degrees(nl["residual"]),
            "max_sway_linear_deg": math.degrees(sway["linear"]["max"]),
            "residual_sway_linear_deg": math.degrees(sway["linear"]["residual"]),
            "residual_sway_linear_exact_deg": math.degrees(residual_linear_exact(
                law, p, sc.t_k, H, self.g)),
            "max_sway_paper_eq9_deg": math.degrees(sway["paper"]["max"]),
            "T_load_mean_J": float(T_load),
            "peak_load_weight_torque_Nm": float(np.abs(load_torque).max()),
            "max_alpha_deg": math.degrees(al.max()),
            "min_alpha_deg": math.degrees(al.min()),
        }
        series = {"alpha": al, "speed": d1 / sc.t_k, "motor_torque": torque,
                  "kinetic_energy": T, "sway": nl["psi"], "sway_linear": sway["linear"]["psi"]}
        return fig, series


def analyse(model, file=None, collocation=True, sensitivity=True, samples=801):
    """The luffing analysis of a scene: a `LuffingResult`.

    Length: one straight sequence of the analysis's steps, each a call; splitting it
    would only pass its dozen intermediate results between functions.
    """
    t0 = time.perf_counter()
    timings = {}
    scene = read_scene(model, file)
    lf = Luffing(model, scene, file)
    timings["kinematics"] = time.perf_counter() - t0
    p, sc = lf.proxy, scene

    grid = np.linspace(lf.alpha0, lf.alphak, 241)
    kin = lf.reduced.evaluate(grid)
    ratio = lf.reduced.ratio * kin["ds"]
    t1 = time.perf_counter()
    laws = lf.laws()
    j = "J" if sc.inertia == "complete" else "Jp"
    T_opt = lf.optimal_energy(laws["optimal"])
    table, series = {}, {}
    for name in ALL_LAWS:
        table[name], series[name] = lf.figures(laws[name], T_opt, samples)
    timings["laws"] = time.perf_counter() - t1
    other = "Jp" if j == "J" else "J"
    opt_paper = laws["optimal_paper"]
    tau = np.linspace(0, 1, 401)
    optimum = {
        "inertia": sc.inertia,
        "T_mean_J": T_opt,
        # the paper's optimum: eq. 16 with the paper's eq. 3 inertia, and its eq. 3 energy
        "T_mean_paper_J": lf.optimal_energy(opt_paper),
        "T_mean_of_paper_law_J": lf.mean_energy(opt_paper, j),
        "paper_law_energy_excess": lf.mean_energy(opt_paper, j) / T_opt - 1,
        "max_law_difference_deg": math.degrees(float(np.abs(
            laws["optimal"].evaluate(tau)[0] - opt_paper.evaluate(tau)[0]).max())),
        "J_paper_over_complete": [float((kin[other] / kin[j]).min()),
                                  float((kin[other] / kin[j]).max())],
        "speed_start_rad_s": float(laws["optimal"].evaluate(0.0)[1][0] / sc.t_k),
        "speed_end_rad_s": float(laws["optimal"].evaluate(1.0)[1][0] / sc.t_k),
        "motor_impulse_Nms": table["optimal"]["motor_impulse_Nms"],
        "coasting_motor_torque_Nm": table["optimal"]["peak_motor_torque_Nm"],
        "rest_to_rest_tau_s": sc.rest_to_rest_tau,
        "rest_to_rest_energy_excess": table["rest_to_rest"]["T_ratio"] - 1,
        "swing_free_energy_excess": table["swing_free"]["T_ratio"] - 1,
        "swing_free_status": int(laws["swing_free"].status),
    }
    result = LuffingResult(
        status=0, message="ok", model_name=model.name, scene=model.scene or "",
        alpha0=lf.alpha0, alphak=lf.alphak, t_k=sc.t_k,
        reach0=float(kin["x"][0]), reachk=float(kin["x"][-1]),
        load_mass=sc.load_mass, rope_length=sc.rope_length, inertia=sc.inertia,
        jib_tip_deviation=float(np.ptp(kin["z"])),
        imbalance_moment=float(np.abs(kin["dV"]).max()),
        imbalance_motor_torque=float(np.abs(kin["dV"] / ratio).max()),
        optimum=optimum, table=table, law_names=ALL_LAWS,
        t=np.linspace(0, sc.t_k, samples),
        alpha=np.array([series[n]["alpha"] for n in ALL_LAWS]),
        speed=np.array([series[n]["speed"] for n in ALL_LAWS]),
        motor_torque=np.array([series[n]["motor_torque"] for n in ALL_LAWS]),
        kinetic_energy=np.array([series[n]["kinetic_energy"] for n in ALL_LAWS]),
        sway=np.array([series[n]["sway"] for n in ALL_LAWS]),
        sway_linear=np.array([series[n]["sway_linear"] for n in ALL_LAWS]),
        alpha_grid=grid, tip_x=kin["x"], tip_z=kin["z"], J=kin["J"], J_paper=kin["Jp"],
        imbalance=kin["dV"], motor_ratio=ratio)
    result.kinematics = {
        "tip_height_mean_m": float(np.mean(kin["z"])),
        "tip_height_range_m": [float(kin["z"].min()), float(kin["z"].max())],
        "tip_slope_max": float(np.abs(kin["dz"] / kin["dx"]).max()),
        "loop_closure_residual": float(lf.linkage.state(grid).residual.max()),
        "proxy_degree": p.degree, "proxy_tail": p.tail,
        "drive_stroke_m": float(np.ptp(kin["s"])),
        "load_weight_motor_torque_max_Nm": float(np.abs(
            sc.load_mass * lf.g * kin["dz"] / ratio).max()),
    }
    if laws["swing_free"].status != 0:
        result.warnings.append(f"swing-free law: solve_bvp {laws['swing_free'].message}")
    if collocation:
        t1 = time.perf_counter()
        result.collocation = collocation_report(lf, laws["optimal"])
        timings["collocation"] = time.perf_counter() - t1
    if sensitivity:
        t1 = time.perf_counter()
        result.sensitivity = sensitivity_report(lf, laws["optimal"])
        timings["sensitivity"] = time.perf_counter() - t1
    timings["total"] = time.perf_counter() - t0
    result.timings = timings
    return result


def law_figures(model, names, samples=801):
    """{law: figures} of the laws `names` only (what a sweep asks for); the same numbers
    as `analyse(model).table`."""
    lf = Luffing(model, read_scene(model))
    laws = lf.laws(names)
    T_opt = lf.optimal_energy(laws["optimal"])
    return {n: lf.figures(laws[n], T_opt, samples)[0] for n in names}


def collocation_report(lf, exact, ns=range(2, 11)):
    """Errors of the paper's collocation and of n-point collocation against the exact law
    (f from the Chebyshev proxy of the kinematics)."""
    from .optimum import (bvp, chebyshev_points, collocation, equally_spaced, law_error,
                          paper_collocation)
    which = lf.scene.inertia
    f = lambda a: lf.proxy.f(a, which)        # noqa: E731
    a0, ak = lf.alpha0, lf.alphak
    out = {"paper": {}}
    for variant in ("printed", "eq21", "corrected"):
        sol = paper_collocation(f, a0, ak, variant)
        info = sol.info
        out["paper"][variant] = {
            "status": sol.status, "message": sol.message, "iterations": sol.iterations,
            "spectral_radius": info.get("spectral_radius"),
            "eigenvalues": info.get("eigenvalues"),
            "relax_best": info.get("relax_best"),
            "spectral_radius_best": info.get("spectral_radius_best"),
            "fixed_point": info["fixed_point"],
            "error_rad": law_error(sol, exact) if info["fixed_point_found"] else None}
    best = out["paper"]["corrected"]["relax_best"]
    if best is not None:
        sol = paper_collocation(f, a0, ak, "corrected", relax=best)
        out["paper"]["corrected_relaxed"] = {
            "status": sol.status, "message": sol.message, "iterations": sol.iterations,
            "relax": best, "error_rad": law_error(sol, exact)}
    for kind, points in (("equally_spaced", equally_spaced), ("chebyshev", chebyshev_points)):
        rows = []
        for n in ns:
            sol = collocation(f, a0, ak, points(n), df=lambda a: _df(lf, a, which))
            rows.append({"n": n, "error_rad": law_error(sol, exact), "status": sol.status,
                         "iterations": sol.iterations})
        out[kind] = rows
        out[kind + "_rate"] = convergence_rate(rows)
    sol = bvp(f, a0, ak, tol=1e-8)
    out["solve_bvp"] = {"tol": 1e-8, "error_rad": law_error(sol, exact),
                        "nodes": sol.info["nodes"], "status": sol.status}
    return out


def _df(lf, a, which):
    j = "J" if which == "complete" else "Jp"
    p = lf.proxy
    J, dJ = p(j, a), p("d" + j, a)
    return 0.5 * (p.derivative("d" + j, a) / J - dJ**2 / J**2)


def convergence_rate(rows):
    """Fits of the error against n: geometric (error ~ C r^n: r) and algebraic
    (error ~ C n^-p: p), over the points above the round-off floor (1e-12 rad)."""
    n = np.array([r["n"] for r in rows], dtype=float)
    e = np.array([r["error_rad"] for r in rows])
    sel = e > 1e-12
    if sel.sum() < 2:
        return {"geometric_ratio": None, "algebraic_order": None}
    slope = np.polyfit(n[sel], np.log(e[sel]), 1)[0]
    order = -np.polyfit(np.log(n[sel]), np.log(e[sel]), 1)[0]
    return {"geometric_ratio": float(np.exp(slope)), "algebraic_order": float(order),
            "digits_per_point": float(-slope / np.log(10))}


def sensitivity_report(lf, exact):
    """The optimum against the luffing time, the load and the rope length."""
    from .laws import rest_to_rest_law
    from .sway import TipMotion, simulate, swing_free_law
    sc, p, g = lf.scene, lf.proxy, lf.g
    base_T = exact.info["S"] ** 2 / (2 * sc.t_k**2)
    rows_t = []
    for factor in (0.5, 0.75, 1.0, 1.5, 2.0):
        tk = sc.t_k * factor
        T = exact.info["S"] ** 2 / (2 * tk**2)
        tip = TipMotion(exact, p, tk)
        res = simulate(tip, sc.rope_length, g, "nonlinear", samples=201)
        sf = swing_free_law(p, lf.alpha0, lf.alphak, tk, sc.rope_length, g, exact,
                            which=sc.inertia)
        sf_T = _mean(lf, sf, tk)
        rr = rest_to_rest_law(p, lf.alpha0, lf.alphak, sc.rest_to_rest_tau, tk, sc.inertia)
        tq = np.abs(_torque(lf, rr, tk)).max()
        rows_t.append({"t_k_s": tk, "T_mean_J": T, "T_over_base": T / base_T,
                       "residual_sway_optimal_deg": math.degrees(res["residual"]),
                       "max_sway_optimal_deg": math.degrees(res["max"]),
                       "swing_free_energy_excess": sf_T / T - 1 if sf.status == 0 else None,
                       "rest_to_rest_peak_motor_torque_Nm": float(tq)})
    rows_m = []
    tau = np.linspace(0, 1, 201)
    for factor in (0.0, 0.5, 1.0, 1.5):
        m = sc.load_mass * factor

        def extra(al, m=m):          # the load carried rigidly at the tip
            return (m * (p("dx", al) ** 2 + p("dz", al) ** 2),
                    2 * m * (p("dx", al) * p("ddx", al) + p("dz", al) * p("ddz", al)))

        law = lf.optimal(extra_inertia=extra, name=f"optimal m={m:g}")
        T_with = law.info["S"] ** 2 / (2 * sc.t_k**2)
        rows_m.append({"load_mass_kg": m, "T_mean_with_load_J": T_with,
                       "T_links_of_that_law_J": lf.mean_energy(law),
                       "max_law_difference_deg": math.degrees(float(np.abs(
                           law.evaluate(tau)[0] - exact.evaluate(tau)[0]).max()))})
    rows_h = []
    for factor in (0.5, 1.0, 2.0):
        H = sc.rope_length * factor
        tip = TipMotion(exact, p, sc.t_k)
        res = simulate(tip, H, g, "nonlinear", samples=201)
        sf = swing_free_law(p, lf.alpha0, lf.alphak, sc.t_k, H, g, exact, which=sc.inertia)
        rows_h.append({"rope_length_m": H, "residual_sway_optimal_deg":
                       math.degrees(res["residual"]),
                       "swing_free_energy_excess": _mean(lf, sf, sc.t_k) / base_T - 1
                       if sf.status == 0 else None})
    return {"t_k": rows_t, "load_mass": rows_m, "rope_length": rows_h,
            "note": "the optimum of eq. 16 does not depend on the load (its terms cancel "
                    "with eq. 9); load_mass rows carry the load rigidly at the tip"}


def _mean(lf, law, tk):
    return lf.mean_energy(law) * lf.scene.t_k**2 / tk**2


def _torque(lf, law, tk, samples=401):
    p = lf.proxy
    al, d1, d2 = law.evaluate(np.linspace(0, 1, samples))
    Q = (p("J", al) * d2 + 0.5 * p("dJ", al) * d1**2) / tk**2 + p("dV", al)
    return Q / (lf.reduced.ratio * p("ds", al))
