"""Peer benchmark: the paper's slider-crank built with Exudyn (pip package ``exudyn``).

Written from Exudyn's public Python API only (no jointdyn code is used to build or solve the
model), so that the numbers compare two independent implementations of the same mechanism
(benchmark definition, docs/theory.md [T160]):

* crank (0.05 m, 0.30 kg, I 1e-4), rod (0.12 m, 0.21 kg, I 2.5e-4), slider (0.14 kg, I 1e-4),
  CoMs at mid-length, slider on the global x axis through the crank pivot, gravity 9.81 m/s^2
  along -y, crank driven at 5000 rpm (523.599 rad/s) CCW from angle 0 at t = 0;
* output: the crank driving moment (torque the drive applies to the crank, CCW positive) at
  ``n_out`` equally spaced times on [0, t_end].

Modelling choices (Exudyn side)
-------------------------------
* Bodies: ``NodeRigidBody2D`` + ``ObjectRigidBody2D`` (node at the CoM; coordinates x, y, phi).
* Joints: ``ObjectJointRevolute2D`` (crank-ground, crank-rod, rod-slider in the perfect case),
  ``ObjectJointPrismatic2D`` ground-slider along global x with ``constrainRotation=True``.
* Drive: ``CoordinateConstraint`` (ObjectConnectorCoordinate) between a ground coordinate and
  the crank's rotation coordinate with ``offsetUserFunction = omega*t`` (and its derivative in
  ``offsetUserFunction_t``); its Lagrange multiplier (``OutputVariableType.Force``, recorded by a
  ``SensorObject`` every step) is the reaction; the driving moment is its negative (sign checked
  against the analytic inverse dynamics, see tests/test_peers_exudyn.py).
* Solver: implicit, fixed step
  ``h`` (``adaptiveStep=False``); Newton relative tolerance 1e-10 (perfect) or Exudyn's default
  1e-8 (dry: 1e-10 cannot be reached at some impacts and generalized-alpha then stops).
  Default solver: ``TrapezoidalIndex2`` (implicit trapezoidal rule, index-2 constraints): its
  multiplier is second-order accurate from t = 0, whereas index-3 generalized-alpha
  (rho_inf = 0.9) has a start-up oscillation of the multiplier (~1e-2 of the peak at h = 1e-5,
  decaying over ~0.003 s); ``solver="GeneralizedAlpha"`` selects the latter. Exudyn's explicit
  solvers cannot be used here: they only handle coordinate constraints to ground (eliminated),
  not revolute/prismatic joints.
* Output at ``n_out`` times: the per-step multipliers are interpolated (cubic spline for the
  smooth perfect case, linear for the dry case, whose spikes a spline would overshoot).

Dry clearance (rod-slider)
--------------------------
No rod-slider joint; an ``ObjectConnectorCartesianSpringDamper`` between a marker at the rod end
(the bearing centre, rod eye) and a marker at the slider CoM (journal centre) with a Python
``springForceUserFunction``. Exudyn hands it e = P_slider - P_rodend (``displacement``) and its
rate (``velocity``); it returns f = F_n u, which the connector applies as -f on the journal and
+f on the rod eye (at the rod end point, so the rod also gets the moment of its arm). A
connector rather than a load because Exudyn differentiates connector forces numerically for the
Newton Jacobian (observed: ~13 extra user-function calls per Jacobian update), which the
6.9e10 N/m^1.5 contact stiffness needs; loads are left out of the Jacobian by default.
Lankarani-Nikravesh:
F_n = K delta^1.5 [1 + 3(1 - c_r^2)/4 * deltadot/deltadot_minus], clamped >= 0, frictionless.

deltadot_minus (penetration rate at contact onset) is Python-side state updated by a
``PreStepUserFunction`` from the accepted state at the start of each step: when that state is in
contact (delta > 0) and the previous one was not, deltadot_minus := deltadot of that state and
an impact is counted; when it is out of contact the latch is cleared. During the step in which
contact begins (no latch yet) the force function uses the current iterate's own deltadot as
deltadot_minus (damping factor 1 + 3(1-c_r^2)/4 at onset, consistent with the definition).
Max penetration and the impact count are taken from the accepted step-end states.
"""

from __future__ import annotations

import math
import time

import numpy as np

# ----------------------------------------------------------------------------- mechanism data
R_CRANK, L_ROD = 0.05, 0.12
M = (0.30, 0.21, 0.14)  # crank, rod, slider [kg]
IZZ = (1.0e-4, 2.5e-4, 1.0e-4)  # [kg m^2]
G = 9.81
OMEGA = 5000 * 2 * math.pi / 60  # 523.5988 rad/s
T_END = 4 * 2 * math.pi / OMEGA  # 4 revolutions, 0.048 s
N_OUT = 1441

# dry clearance joint
R_B, R_J = 10.5e-3, 10.0e-3
C_CLEAR = R_B - R_J
SIGMA = (1 - 0.3**2) / 207e9
K_LN = (4.0 / 3.0) / (2 * SIGMA) * math.sqrt(R_B * R_J / (R_B - R_J))
C_R = 0.9
HYST = 3 * (1 - C_R**2) / 4

_IMPORT_MSG = "install the [peers] extra: pip install -e .[peers]"


def _exudyn():
    try:
        import exudyn as exu
        import exudyn.itemInterface as ii
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise ImportError(_IMPORT_MSG) from err
    return exu, ii


def _build(h: float, t_end: float, joint: str, opts: dict | None = None):
    """Build the Exudyn model; returns (SC, mbs, settings, handles)."""
    exu, ii = _exudyn()
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    r, l, w = R_CRANK, L_ROD, OMEGA

    oGround = mbs.AddObject(ii.ObjectGround())
    nGround = mbs.AddNode(ii.NodePointGround())
    mGroundCoord = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))

    def body(pos, vel, m, izz):
        n = mbs.AddNode(
            ii.NodeRigidBody2D(referenceCoordinates=[pos[0], pos[1], 0.0], initialVelocities=list(vel))
        )
        b = mbs.AddObject(ii.ObjectRigidBody2D(nodeNumber=n, mass=m, inertia=izz))
        return n, b

    # initial state: crank angle 0, all bodies on the x axis; velocities of the ideal mechanism
    beta_d0 = -w * r / l  # rod angular velocity at theta = 0: -218.166 rad/s
    nC, bC = body((r / 2, 0.0), (0.0, w * r / 2, w), M[0], IZZ[0])
    vA = w * r  # crank pin velocity (along +y)
    nR, bR = body((r + l / 2, 0.0), (0.0, vA + beta_d0 * l / 2, beta_d0), M[1], IZZ[1])
    nS, bS = body((r + l, 0.0), (0.0, vA + beta_d0 * l, 0.0), M[2], IZZ[2])  # = (0, 0, 0)

    for b in (bC, bR, bS):
        mc = mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=b))
        mbs.AddLoad(ii.LoadMassProportional(markerNumber=mc, loadVector=[0.0, -G, 0.0]))

    # crank-ground revolute
    mG0 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=oGround, localPosition=[0.0, 0.0, 0.0]))
    mC0 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bC, localPosition=[-r / 2, 0.0, 0.0]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[mG0, mC0]))
    # crank-rod revolute
    mC1 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bC, localPosition=[r / 2, 0.0, 0.0]))
    mR0 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bR, localPosition=[-l / 2, 0.0, 0.0]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[mC1, mR0]))
    # rod end (bearing centre) and slider CoM (journal centre)
    mR1 = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bR, localPosition=[l / 2, 0.0, 0.0]))
    mS = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bS, localPosition=[0.0, 0.0, 0.0]))
    # ground-slider prismatic along global x, rotation locked
    mGR = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=oGround, localPosition=[0.0, 0.0, 0.0]))
    mSR = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=bS, localPosition=[0.0, 0.0, 0.0]))
    mbs.AddObject(
        ii.ObjectJointPrismatic2D(
            markerNumbers=[mGR, mSR],
            axisMarker0=[1.0, 0.0, 0.0],
            normalMarker1=[0.0, 1.0, 0.0],
            constrainRotation=True,
        )
    )
    # crank drive: phi_crank - omega t = 0
    mCphi = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nC, coordinate=2))
    oDrive = mbs.AddObject(
        ii.CoordinateConstraint(
            markerNumbers=[mGroundCoord, mCphi],
            offsetUserFunction=lambda mbs_, t, item, off: w * t,
            offsetUserFunction_t=lambda mbs_, t, item, off: w,
        )
    )
    sDrive = mbs.AddSensor(
        ii.SensorObject(
            objectNumber=oDrive,
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Force,
        )
    )

    state = None
    if joint == "perfect":
        mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[mR1, mS]))
    elif joint == "dry":
        state = _DryState()
        mbs.AddObject(
            ii.ObjectConnectorCartesianSpringDamper(
                markerNumbers=[mR1, mS],
                stiffness=[0.0, 0.0, 0.0],
                damping=[0.0, 0.0, 0.0],
                springForceUserFunction=state.force,
            )
        )
        mbs.SetPreStepUserFunction(state.make_prestep(exu, nR, nS))
    else:
        raise ValueError(joint)

    mbs.Assemble()

    n_steps = max(1, int(round(t_end / h)))
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps = n_steps
    ti.endTime = t_end
    ti.adaptiveStep = False
    ti.verboseMode = 0
    if joint == "perfect":  # tight Newton tolerances: the perfect case is an accuracy study
        ti.newton.relativeTolerance = 1e-10
        ti.newton.absoluteTolerance = 1e-12
    else:  # Exudyn's defaults; 1e-10 is unreachable at some impacts (generalized-alpha fails)
        ti.newton.relativeTolerance = 1e-8
        ti.newton.absoluteTolerance = 1e-10
    ti.generalizedAlpha.spectralRadius = 0.9
    ti.generalizedAlpha.computeInitialAccelerations = True
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 0.5 * t_end / n_steps  # every step
    for k, v in (opts or {}).items():  # dotted overrides, e.g. {"generalizedAlpha.spectralRadius": 0.6}
        obj = ti
        *path, last = k.split(".")
        for a in path:
            obj = getattr(obj, a)
        setattr(obj, last, v)
    s.show.computationTime = False
    s.show.statistics = False
    return SC, mbs, s, {"sDrive": sDrive, "n_steps": n_steps, "state": state, "nR": nR, "nS": nS}


class _DryState:
    """Python-side contact state: latched onset penetration rate, impact count, max penetration."""

    def __init__(self):
        self.dd_minus = None  # latched deltadot at onset (None: not in contact at last step end)
        self.impacts = 0
        self.max_pen = 0.0
        self.first_pen = 0.0  # largest penetration of the first contact episode [m]
        self.first_pen_hermite = 0.0  # the same, peaks between step ends included (see observe)
        self.last = None  # (t, delta, deltadot) of the previous accepted step end
        self.calls = 0

    def force(self, mbs, t, item, e, edot, stiffness, damping, offset):
        self.calls += 1
        ex, ey = e[0], e[1]
        d = math.sqrt(ex * ex + ey * ey)
        delta = d - C_CLEAR
        if delta <= 0.0:
            return [0.0, 0.0, 0.0]
        ux, uy = ex / d, ey / d
        dd = edot[0] * ux + edot[1] * uy  # penetration rate
        ddm = self.dd_minus if self.dd_minus is not None else dd
        fac = 1.0 + HYST * dd / ddm if ddm > 1e-12 else 1.0
        fn = K_LN * delta**1.5 * fac
        if fn <= 0.0:
            return [0.0, 0.0, 0.0]
        return [fn * ux, fn * uy, 0.0]

    def observe(self, e, edot, t=None):
        d = math.hypot(e[0], e[1])
        delta = d - C_CLEAR
        if delta > 0.0:
            self.max_pen = max(self.max_pen, delta)
            if self.dd_minus is None:
                self.impacts += 1
                self.dd_minus = (edot[0] * e[0] + edot[1] * e[1]) / d
            if self.impacts == 1:
                self.first_pen = max(self.first_pen, delta)
        else:
            self.dd_minus = None
        if t is not None and self.impacts <= 1:  # (nothing more once the first episode is over)
            dd = (edot[0] * e[0] + edot[1] * e[1]) / d if d > 0.0 else 0.0
            self._first_peak_between_steps(t, delta, dd)

    def _first_peak_between_steps(self, t, delta, dd):
        """The first episode's peak between two step ends: maximum of the cubic Hermite
        interpolant of delta(t) through (delta, deltadot) at both ends, on a grid (an analysis
        of the stored step-end states, as jointdyn's max_penetration does, docs/theory.md)."""
        if self.last is not None and self.impacts == 1 and self.last[2] > 0.0 > dd:
            t0, d0, v0 = self.last
            h = t - t0
            th = np.linspace(0.0, 1.0, 1001)
            p = (
                (1 + 2 * th) * (1 - th) ** 2 * d0
                + th * (1 - th) ** 2 * h * v0
                + th**2 * (3 - 2 * th) * delta
                + th**2 * (th - 1) * h * dd
            )
            self.first_pen_hermite = max(self.first_pen_hermite, float(p.max()))
        self.first_pen_hermite = max(self.first_pen_hermite, self.first_pen)
        self.last = (t, delta, dd)

    def make_prestep(self, exu, nR, nS):
        P, V, A = (
            exu.OutputVariableType.Position,
            exu.OutputVariableType.Velocity,
            exu.OutputVariableType.Rotation,
        )
        W = exu.OutputVariableType.AngularVelocity
        hl = L_ROD / 2

        def rod_end(mbs):
            pr = mbs.GetNodeOutput(nR, P)
            vr = mbs.GetNodeOutput(nR, V)
            phi = mbs.GetNodeOutput(nR, A)
            phi = float(np.ravel(phi)[-1])
            om = float(np.ravel(mbs.GetNodeOutput(nR, W))[-1])
            c, s = math.cos(phi), math.sin(phi)
            p = (pr[0] + hl * c, pr[1] + hl * s)
            v = (vr[0] - om * hl * s, vr[1] + om * hl * c)
            return p, v

        def prestep(mbs, t):
            p, v = rod_end(mbs)
            ps, vs = mbs.GetNodeOutput(nS, P), mbs.GetNodeOutput(nS, V)
            self.observe((ps[0] - p[0], ps[1] - p[1]), (vs[0] - v[0], vs[1] - v[1]), t)
            return True

        self.prestep = prestep
        return prestep


def _run(
    h: float, t_end: float, n_out: int, joint: str, opts: dict | None = None, solver: str = "GeneralizedAlpha"
) -> dict:
    exu, _ = _exudyn()
    t0 = time.perf_counter()
    SC, mbs, s, hd = _build(h, t_end, joint, opts)
    build_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    ok = mbs.SolveDynamic(s, solverType=getattr(exu.DynamicSolverType, solver))
    wall_s = time.perf_counter() - t0
    if not ok:
        raise RuntimeError(f"Exudyn SolveDynamic failed ({joint}, h={h})")
    st = hd["state"]
    if st is not None:  # observe the final state too
        st.prestep(mbs, t_end)
    data = mbs.GetSensorStoredData(hd["sDrive"])
    ts, lam = data[:, 0], data[:, 1]
    moment_steps = -lam  # driving moment = -multiplier (sign verified against inverse dynamics)
    t_out = np.linspace(0.0, t_end, n_out)
    if joint == "perfect":
        from scipy.interpolate import CubicSpline

        # sensors may repeat the first time (initial value): keep strictly increasing times
        keep = np.concatenate([[True], np.diff(ts) > 0])
        moment = CubicSpline(ts[keep], moment_steps[keep])(t_out)
    else:
        moment = np.interp(t_out, ts, moment_steps)
    return {
        "t": t_out,
        "crank_moment": moment,
        "wall_s": wall_s,
        "build_s": build_s,
        "steps": hd["n_steps"],
        "max_penetration": None if st is None else st.max_pen,
        "impacts": None if st is None else st.impacts,
        "first_penetration": None if st is None else st.first_pen,
        "first_penetration_hermite": None if st is None else st.first_pen_hermite,
        "t_steps": ts,
        "crank_moment_steps": moment_steps,
    }


def exudyn_perfect(
    h: float, t_end: float = T_END, n_out: int = N_OUT, *, solver: str = "TrapezoidalIndex2"
) -> dict:
    """Perfect joints at fixed step h (Exudyn implicit trapezoidal rule, index-2 constraints,
    by default). Crank driving moment at n_out equally spaced times on [0, t_end]."""
    return _run(h, t_end, n_out, "perfect", solver=solver)


def exudyn_dry(
    h: float, t_end: float = T_END, n_out: int = N_OUT, *, solver: str = "TrapezoidalIndex2"
) -> dict:
    """Dry clearance joint (Lankarani-Nikravesh) between rod and slider at fixed step h."""
    return _run(h, t_end, n_out, "dry", solver=solver)


def analytic_moment(t, omega: float = OMEGA):
    """Inverse-dynamics crank moment of the ideal mechanism (power balance), for the table."""
    r, l = R_CRANK, L_ROD
    th = omega * t
    s, c = np.sin(th), np.cos(th)
    sb = -r * s / l
    cb = np.sqrt(1 - sb**2)
    bd = -r * omega * c / (l * cb)
    bdd = (r * omega**2 * s + l * sb * bd**2) / (l * cb)
    vA = np.stack([-r * omega * s, r * omega * c])
    aA = np.stack([-r * omega**2 * c, -r * omega**2 * s])
    vBx = -r * omega * s - l * sb * bd
    aBx = -r * omega**2 * c - l * cb * bd**2 - l * sb * bdd
    vB, aB = np.stack([vBx, 0 * t]), np.stack([aBx, 0 * t])
    v1, a1, v2, a2 = vA / 2, aA / 2, (vA + vB) / 2, (aA + aB) / 2
    p = (
        M[0] * (v1 * a1).sum(0)
        + M[1] * (v2 * a2).sum(0)
        + IZZ[1] * bd * bdd
        + M[2] * vB[0] * aB[0]
        + G * (M[0] * v1[1] + M[1] * v2[1])
    )
    return p / omega


def _table(argv=None):
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--revs", type=float, default=4.0, help="crank revolutions (default 4)")
    ap.add_argument("--perfect-h", default="1e-4,3e-5,1e-5,3e-6,2.5e-6,1e-6")
    ap.add_argument("--dry-h", default="1e-5,1e-6")
    ap.add_argument(
        "--solver",
        default="TrapezoidalIndex2",
        help="Exudyn DynamicSolverType: TrapezoidalIndex2 or GeneralizedAlpha",
    )
    ap.add_argument("--repeat", type=int, default=3, help="runs per case; median wall time")
    a = ap.parse_args(argv)
    exu, _ = _exudyn()
    t_end = a.revs * 2 * math.pi / OMEGA
    t_rev = 2 * math.pi / OMEGA
    print(
        f"Exudyn {exu.__version__}, solver {a.solver}, fixed step, t_end = {t_end:.6f} s "
        f"({a.revs:g} rev), {N_OUT} output points; wall = SolveDynamic only, median of {a.repeat}"
    )

    def timed(fn, h):
        runs = [fn(h, t_end, N_OUT, solver=a.solver) for _ in range(max(1, a.repeat))]
        walls = sorted(r["wall_s"] for r in runs)
        res = runs[0]
        res["wall_s"] = walls[len(walls) // 2]
        return res

    print("\nperfect joints (error vs analytic inverse dynamics, relative to its peak)")
    print(
        f"{'h [s]':>9} {'steps':>7} {'wall [s]':>9} {'build [s]':>9} {'peak':>9} {'min':>9} {'err/peak':>9}"
    )
    for h in [float(x) for x in a.perfect_h.split(",") if x]:
        r = timed(exudyn_perfect, h)
        Mref = analytic_moment(r["t"])
        err = np.abs(r["crank_moment"] - Mref).max() / np.abs(Mref).max()
        print(
            f"{h:9.1e} {r['steps']:7d} {r['wall_s']:9.3f} {r['build_s']:9.3f} "
            f"{r['crank_moment'].max():9.3f} {r['crank_moment'].min():9.3f} {err:9.2e}"
        )

    print(
        f"\ndry clearance rod-slider (Lankarani-Nikravesh, K = {K_LN:.4g}, c_r = {C_R:g}, c = {C_CLEAR:g} m)"
    )
    print(
        f"{'h [s]':>9} {'steps':>7} {'wall [s]':>9} {'impacts':>8} {'max pen [m]':>12} "
        f"{'peak':>9} {'min':>9} {'RMS all':>9} {'RMS last':>9}"
    )
    for h in [float(x) for x in a.dry_h.split(",") if x]:
        try:
            r = timed(exudyn_dry, h)
        except Exception as err:  # report an Exudyn solver failure instead of aborting the table
            print(f"{h:9.1e}  failed: {err}")
            continue
        ts, Ms = r["t_steps"], r["crank_moment_steps"]
        last = ts >= t_end - t_rev * (1 - 1e-9)
        rms_last = float(np.sqrt(np.mean(Ms[last] ** 2)))  # per-step samples of the last rev
        print(
            f"{h:9.1e} {r['steps']:7d} {r['wall_s']:9.3f} {r['impacts']:8d} "
            f"{r['max_penetration']:12.3e} {Ms.max():9.1f} {Ms.min():9.1f} "
            f"{np.sqrt(np.mean(Ms**2)):9.2f} {rms_last:9.2f}"
        )
    print(
        "(dry: peak/min/RMS from the per-step multipliers, not the interpolated output; "
        "impacts and max penetration from accepted step-end states)"
    )


if __name__ == "__main__":
    _table()
