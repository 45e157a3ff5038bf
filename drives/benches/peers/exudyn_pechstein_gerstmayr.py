#!/usr/bin/env python3
"""Peer model of the Pechstein & Gerstmayr (2013) two-pulley belt drive in Exudyn (issue 34, item 7).

The drive of Exudyn's public example `Examples/beltDriveReevingSystem.py` with
`improvedBelt = True` (the "improved belt" of that example), rebuilt here from Exudyn's items
(not a copy of the example; every parameter below names the example's variable it comes from):

* belt: closed loop of `n` `ObjectANCFCable2D` elements (default 120, the example's comment
  "120 works well"; the example file itself runs 240) on the path at radius r + hc/2 over both
  pulleys (r = radiusPulley = 0.09995 m, hc = 0.01·0.01 m, so the centreline radius is 0.1 m;
  centre distance positionPulley2x = 0.1π m; path length 0.4π m, node 0 at (0, 0.1) m, the
  upper tangent point of the left pulley, nodes ordered clockwise as CreateReevingCurve lays
  them; the belt travels counter-clockwise). Reference element length = path length / n, unit slopes: the belt is laid stress-free
  in the reference sense and its pre-tension comes from physicsReferenceAxialStrain
  ε0 = preStretch = −0.05;
* material (Exudyn's cable, its only built-in law): axial force N = EA·(|r'| − 1 − ε0) + dEA·ε̇
  with EA = E·b·hcStiff = 1e7·0.08·0.01 = 8000 N and dEA = 1 N s; bending moment
  EI·K with EI = 0.02·E·b·hcStiff³/12 = 1.333e-3 N m² (the example's EI *= 0.02), no bending
  damping; ρA = 1036·0.08·0.01 = 0.8288 kg/m; gravity −9.81 m/s² in y on the belt
  (massProportionalLoad); `useReducedOrderIntegration = 2` (axial strain at 0, L/2, L).
  N is linear in the engineering strain |r'| − 1 of the reference length: "pre-strain −5 %"
  means N = 400 N at the reference length, i.e. the unstretched length is 0.95·0.4π m and the
  stiffness against the unstretched length is 0.95·EA = 7600 N. `--material svk` replaces the
  law (axialForceUserFunction, a Python callback) by the St Venant–Kirchhoff force
  N = EA0·λ(λ² − 1)/2 with EA0 = 7600 N and λ = |r'|/0.9533, the unstretched length for which
  the laid belt carries the same 400 N (with the linear law's unstretched length 0.95·L it
  would carry 432 N);
* pulleys: `ObjectRigidBody2D` (mass 50 kg, I = 0.25 kg m², wheelMass/wheelInertia), centres
  held by coordinate constraints. Pulley 0 (left) is driven by a velocity-level coordinate
  constraint: ω = 0 until 0.05 s, linear ramp to 12 rad/s at 0.6 s (tAccStart, tAccEnd,
  omegaFinal), counter-clockwise, so the upper span is the tight one. Pulley 1 carries a
  rotational damper d = 2 N m s (rotationDampingWheels, CoordinateSpringDamper to ground) and
  the load torque −25·SmoothStep(t, 1, 1.5) N m (UFforce; its release after 3.5 s is left out:
  the peer stops before it);
* contact: one `ObjectContactFrictionCircleCable2D` per element and pulley, nSegments = 2
  linear segments per element on the belt's inner face (MarkerBodyCable2DShape verticalOffset
  −hc/2), contact circle r, segment normals (the item's default). Per segment, with
  c = b·l_el/nSegments (cFact): k = 1e8·c·40, d = 2000·c·40 (normal), and the friction law
  (`--friction`):
  - `bristle` (the example's improvedBelt, useBristleModel): tangential stiffness
    μ_k = 1e8·c·50 and velocity penalty μ_v = 10·sqrt(1e8·c·ρA·l_el/nSegments), the linear
    force μ_v·v_t + μ_k·Δx_stick capped at μ|f_n| (μ = dryFriction = 0.5): an elastic-plastic
    (stick/slip) law whose stick displacement is μ f_n/μ_k ≈ 8 µm at the tight span's
    pressure;
  - `velocity` (the 2013 paper's law, the example's comment "1e7 is original in 2013 paper"):
    μ_k = 0, μ_v = 1e7·c, |f_t| = min(μ_v|v_t|, μ|f_n|), i.e. Coulomb regularised by a slip
    velocity v_s = μ f_n / μ_v (per length: μ_v/l_seg = 1e7·b = 8e5 N s/m², v_s ≈ 4 mm/s at the
    tight side's 6.7 kN/m pressure): flowmbd's `creep_rate` law with creep = 8e5 kg/(m s).
  `--friction-scale s` multiplies μ_k and μ_v (s > 1: towards Coulomb);
* initial state: the example's static equilibrium (friction off, both pulley angles and node
  0's x held, velocity drive off), then released;
* integrator: the example's `TrapezoidalIndex2` (Newmark/trapezoidal with index-2 constraints),
  h = 1e-4 s, modified Newton, discontinuous iteration tolerance 1e-3, at most 3 iterations,
  EigenSparse, one thread (the example sets `parallel.numberOfThreads = 1`); everything else
  Exudyn's defaults (adaptive step on, Newton tolerances 1e-8 / 1e-10).
  The example's general contact (two spheres, no cable in it) exerts no force and is left out.

Measured over the window [t_end − window, t_end] (sampled every `--force-sample` s at the start
of a step, i.e. on the last accepted state): driven and driver speeds, speed loss, the span
tensions (ForceLocal of the cables: the element's own axial force N above, the force of its
virtual work, at the element nodes and midpoints whose position lies in the middle half of a
span), the contact torque on each pulley r·Σ f_t (the circle torque of the contact item), the
driver torque from the velocity constraint, (T1 − T2)·r with the centreline radius 0.1 m and
with r, the applied torque on the driven pulley (load + damper, mean of 25 + 2ω), the belt's
speed along each span (mean ẋ) and its transverse rms speed, and two creep estimates of the
speed loss: 1 − λ_s/λ_t from the span tensions (λ = |r'| of the material law at that force)
and 1 − v_s/v_t from the span speeds. `--wrap-profile` adds the contact along both wraps in the
final state (pressure, friction per metre, relative velocity, axial force by angle).

Prints one JSON object on stdout. Usage (figures and convergence: PECHSTEIN_GERSTMAYR.md):
  exudyn_pechstein_gerstmayr.py [--elements 120] [--segments 2] [--h 1e-4] [--t-end 2.45]
      [--window 0.45] [--friction bristle|velocity] [--friction-scale 1]
      [--material linear|svk] [--damping 2] [--solver trapezoidal|galpha] [--rho-inf 0.9]
      [--reference-scale 1] [--wrap-profile]
"""

import argparse
import json
import math
import sys
import time

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    CoordinateConstraint,
    CoordinateSpringDamper,
    Gravity,
    LoadCoordinate,
    MarkerBodyCable2DShape,
    MarkerBodyMass,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodeGenericData,
    NodePoint2DSlope1,
    NodePointGround,
    NodeRigidBody2D,
    ObjectANCFCable2D,
    ObjectContactFrictionCircleCable2D,
    ObjectGround,
    ObjectRigidBody2D,
    SensorNode,
)

# beltDriveReevingSystem.py, improvedBelt = True
E_MOD = 1.0e7  # Emodulus [Pa]
B = 0.08  # b, width [m]
H_STIFF = 0.01  # hcStiff [m]
HC = 0.01 * 0.01  # hc *= 0.01: geometric height for the contact offset [m]
RHO = 1036.0  # rhoBeam [kg/m3]
EA = E_MOD * B * H_STIFF  # 8000 N
EI = 0.02 * E_MOD * B * H_STIFF**3 / 12.0  # EI *= 0.02 [N m2]
RHO_A = RHO * B * H_STIFF  # 0.8288 kg/m
D_EA = 1.0  # dEA, axial damping [N s]
PRE_STRAIN = -0.05  # preStretch -> physicsReferenceAxialStrain
GRAVITY = 9.81  # gVec = [0, -9.81, 0] on the belt
R = 0.09995  # radiusPulley [m]
R_C = R + 0.5 * HC  # centreline radius of the wrapped belt (radialOffset = hc/2) [m]
DIST = 0.1 * math.pi  # positionPulley2x [m]
MU = 0.5  # dryFriction
WHEEL_MASS = 50.0  # wheelMass [kg]
WHEEL_I = 0.25  # wheelInertia [kg m2]
DAMP_WHEEL = 2.0  # rotationDampingWheels [N m s]
LOAD = 25.0  # UFforce amplitude [N m]
LOAD_T0, LOAD_T1 = 1.0, 1.5  # SmoothStep(t, 1, 1.5)
OMEGA = 12.0  # omegaFinal [rad/s]
T_ACC0, T_ACC1 = 0.05, 0.6  # tAccStart, tAccEnd [s]


def smooth_step(t, t0, t1):
    """exudyn.utilities.SmoothStep(t, t0, t1, 0, 1): half-cosine from 0 to 1."""
    if t <= t0:
        return 0.0
    if t >= t1:
        return 1.0
    return 0.5 * (1.0 - math.cos((t - t0) / (t1 - t0) * math.pi))


def drive_speed(t):
    """UFvelocityDrive: driver angular velocity [rad/s] (counter-clockwise)."""
    if t < T_ACC0:
        return 0.0
    if t < T_ACC1:
        return OMEGA * (t - T_ACC0) / (T_ACC1 - T_ACC0)
    return OMEGA


def path_point(s):
    """Point and unit tangent of the closed path at arc length s: the reeving curve of two
    left-wrapped circles, starting at (0, R_C) and running clockwise (upper span towards +x,
    around pulley 1, lower span towards −x, around pulley 0)."""
    arc = math.pi * R_C
    total = 2.0 * DIST + 2.0 * arc
    s = s % total
    if s < DIST:
        return (s, R_C), (1.0, 0.0)
    s -= DIST
    if s < arc:
        th = math.pi / 2 - s / R_C
        return (DIST + R_C * math.cos(th), R_C * math.sin(th)), (math.sin(th), -math.cos(th))
    s -= arc
    if s < DIST:
        return (DIST - s, -R_C), (-1.0, 0.0)
    s -= DIST
    th = -math.pi / 2 - s / R_C
    return (R_C * math.cos(th), R_C * math.sin(th)), (math.sin(th), -math.cos(th))


def friction_parameters(law, scale, l_el, segments):
    """Per-segment contact and friction coefficients of the example (see module doc)."""
    c = B * l_el / segments  # cFact
    k = 1e8 * c * 40.0
    d = 2000.0 * c * 40.0
    if law == "bristle":
        mu_k = 1e8 * c * 50.0
        mu_v = 10.0 * math.sqrt(1e8 * c * RHO_A * l_el / segments)
    else:  # velocity penalty only: "1e7 is original in 2013 paper" (frictionStiffness = 0)
        mu_k = 0.0
        mu_v = 1e7 * c
    return k, d, mu_k * scale, mu_v * scale


def chord_gap(j, cab, cx, l_el, segments, cables):
    """Gap [m] of contact segment j of cable `cab` against the circle at (cx, 0) in the laid
    configuration (segment points on the inner face, radius R_C − hc/2 = R on the wraps)."""
    i = cables.index(cab)
    pts = []
    for s in ((i + j / segments) * l_el, (i + (j + 1) / segments) * l_el):
        (x, y), (tx, ty) = path_point(s)
        pts.append(np.array([x + 0.5 * HC * ty, y - 0.5 * HC * tx]))  # −hc/2 along the normal (−t_y, t_x)
    a, b = pts
    c = np.array([cx, 0.0])
    u = float(np.clip(np.dot(c - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0))
    return float(np.linalg.norm(a + u * (b - a) - c) - R)


def build(a):
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    n_el = a.elements
    l_path = 2.0 * DIST + 2.0 * math.pi * R_C
    l_el = l_path / n_el

    mbs.AddObject(ObjectGround())
    n_ground = mbs.AddNode(NodePointGround())
    m_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0))

    # `--reference-scale f`: the same physical belt on elements of reference length f·l_el
    # (nodes on the path, slopes t/f, so |r'| = (current length)/(f·l_el)); the law is kept by
    # EA' = f·EA, 1 + ε0' = (1 + ε0)/f, dEA' = f·dEA, ρA' = ρA/f and EI' = f·EI (Exudyn's
    # material curvature (r'×r'')/|r'|² integrated over the reference length). Only the contact's
    # sticking-position bookkeeping, which measures the position along a segment in reference
    # length (CObjectContactFrictionCircleCable2D.cpp, CObjectContactFrictionCircleCable2DuseL),
    # sees f: its error vanishes where the belt's current length equals f·l_el.
    f = a.reference_scale
    l_ref = f * l_el
    nodes = []
    for i in range(n_el):
        p, t = path_point(i * l_el)
        nodes.append(mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[p[0], p[1], t[0] / f, t[1] / f])))

    ea0, c_svk = svk_parameters()

    def svk_force(mbs_, t, item, x_norm, eps, eps_t, eps_ref, ea, d_ea, kap, kap_t, kap_ref):
        # St Venant–Kirchhoff nominal force N = EA0 λ(λ² − 1)/2 of the unstretched length
        # c_svk·L (λ = |r'|/c_svk, |r'| = 1 + eps), plus the same axial damping
        lam = (1.0 + eps) / c_svk
        return ea0 * lam * (lam * lam - 1.0) * 0.5 + d_ea * eps_t

    def linear_moment(mbs_, t, item, x_norm, kap, kap_t, kap_ref, ei, d_ei, eps, eps_t, eps_ref):
        # Exudyn's own bending law EI (K − K0) + d_EI K̇, as a user function only because
        # Exudyn 1.13.6 (and its master at e44aca1b) uses the axial-force user function in the
        # residual only when a bending-moment user function is set too (CObjectANCFCable2D.cpp
        # ComputeODE2LHS tests HasTorqueUserFunction() on the axial branch); without it the
        # dynamics keep the linear law while ForceLocal reports the user function's force
        return ei * (kap - kap_ref) + d_ei * kap_t

    cables = []
    for i in range(n_el):
        kw = {}
        if a.material == "svk":
            kw["axialForceUserFunction"] = svk_force
            kw["bendingMomentUserFunction"] = linear_moment
        cab = mbs.AddObject(
            ObjectANCFCable2D(
                length=l_ref,
                massPerLength=RHO_A / f,
                bendingStiffness=EI * f,
                axialStiffness=EA * f,
                bendingDamping=0.0,
                axialDamping=D_EA * f,
                referenceAxialStrain=(1.0 + PRE_STRAIN) / f - 1.0,
                referenceCurvature=0.0,
                strainIsRelativeToReference=0.0,
                useReducedOrderIntegration=2,
                nodeNumbers=[nodes[i], nodes[(i + 1) % n_el]],
                **kw,
            )
        )
        cables.append(cab)
        if a.gravity != 0.0:
            m_mass = mbs.AddMarker(MarkerBodyMass(bodyNumber=cab))
            mbs.AddLoad(Gravity(markerNumber=m_mass, loadVector=[0.0, -a.gravity, 0.0]))
    # node 0's x held during the static solve only (fixedConstraintsNode0 = [1, 0, 0, 0])
    m_node0 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=0))
    hold_belt = mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_node0]))

    k, d, mu_k, mu_v = friction_parameters(a.friction, a.friction_scale, l_el, a.segments)
    pulleys, bodies, holds, contacts = [], [], [], [[], []]
    for i, cx in enumerate([0.0, DIST]):
        nd = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[cx, 0.0, 0.0]))
        body = mbs.AddObject(ObjectRigidBody2D(mass=WHEEL_MASS, inertia=WHEEL_I, nodeNumber=nd))
        for c in (0, 1):
            mc = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nd, coordinate=c))
            mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, mc]))
        m_rot = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nd, coordinate=2))
        if i == 0:
            vel = mbs.AddObject(
                CoordinateConstraint(
                    markerNumbers=[m_ground, m_rot],
                    velocityLevel=True,
                    offsetUserFunction_t=lambda mbs_, t, item, off: drive_speed(t),
                )
            )
        else:
            if a.damping != 0.0:
                mbs.AddObject(CoordinateSpringDamper(markerNumbers=[m_ground, m_rot], damping=a.damping))
            mbs.AddLoad(
                LoadCoordinate(
                    markerNumber=m_rot,
                    load=0.0,
                    loadUserFunction=lambda mbs_, t, load: -a.load * smooth_step(t, LOAD_T0, LOAD_T1),
                )
            )
        # angle held during the static solve only (wheelSprings)
        holds.append(mbs.AddObject(CoordinateConstraint(markerNumbers=[m_ground, m_rot])))
        pulleys.append(nd)
        bodies.append(body)

        m_circle = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
        for cab in cables:
            m_cable = mbs.AddMarker(
                MarkerBodyCable2DShape(bodyNumber=cab, numberOfSegments=a.segments, verticalOffset=-0.5 * HC)
            )
            if a.initial_gaps == "example":
                gaps = [0.1] * a.segments  # no contact: the static solve's iteration finds it
            else:
                gaps = [chord_gap(j, cab, cx, l_el, a.segments, cables) for j in range(a.segments)]
            data = mbs.AddNode(
                NodeGenericData(
                    initialCoordinates=gaps + [-2] * a.segments + [0.0] * a.segments,
                    numberOfDataCoordinates=3 * a.segments,
                )
            )
            contacts[i].append(
                mbs.AddObject(
                    ObjectContactFrictionCircleCable2D(
                        markerNumbers=[m_circle, m_cable],
                        nodeNumber=data,
                        numberOfContactSegments=a.segments,
                        contactStiffness=k,
                        contactDamping=d,
                        frictionVelocityPenalty=mu_v,
                        frictionStiffness=mu_k,
                        frictionCoefficient=MU,
                        circleRadius=R,
                    )
                )
            )
    sensors = [
        mbs.AddSensor(
            SensorNode(nodeNumber=nd, storeInternal=True, outputVariableType=exu.OutputVariableType.AngularVelocity)
        )
        for nd in pulleys
    ]
    mbs.Assemble()
    return sc, mbs, {
        "cables": cables,
        "l_el": l_ref,
        "reference_scale": f,
        "vel": vel,
        "holds": holds,
        "hold_belt": hold_belt,
        "contacts": contacts,
        "sensors": sensors,
        "friction": {"k": k, "d": d, "mu_k": mu_k, "mu_v": mu_v},
    }


def svk_parameters():
    """St Venant–Kirchhoff variant: the small-strain stiffness of the unstretched section
    EA0 = (1 + ε0)·EA = 7600 N (the linear law's, E·A of the unstretched belt) and the unstretched
    length c·L_ref for which the laid belt (|r'| = 1) carries the same −ε0·EA = 400 N:
    EA0·λ(λ² − 1)/2 = 400 with λ = 1/c (λ = 1.0490, c = 0.9533)."""
    ea0 = (1.0 + PRE_STRAIN) * EA
    t0 = -PRE_STRAIN * EA
    lam = 1.0 + t0 / ea0
    for _ in range(50):
        lam -= (ea0 * lam * (lam * lam - 1.0) * 0.5 - t0) / (ea0 * (1.5 * lam * lam - 0.5))
    return ea0, 1.0 / lam


def stretch(force, material):
    """|r'| of the reference length at the axial force `force` [N] (quasi-static, no damping):
    the inverse of the material law."""
    if material == "linear":
        return 1.0 + PRE_STRAIN + force / EA
    # SVK: N = EA0·λ(λ²−1)/2, |r'| = c λ; Newton from λ = 1
    ea0, c = svk_parameters()
    lam = 1.0
    for _ in range(50):
        lam -= (ea0 * lam * (lam * lam - 1.0) * 0.5 - force) / (ea0 * (1.5 * lam * lam - 0.5))
    return c * lam


def span_points(mbs, model):
    """The element nodes and midpoints in the middle half of the spans: `(output, p)` for each,
    `output(variable)` the cable's output variable there in the current configuration and `p`
    its position (upper, tight span: `p[1] > 0`; lower, slack span otherwise)."""
    x_lo, x_hi = 0.25 * DIST, 0.75 * DIST
    cfg = exu.ConfigurationType.Current
    for cab in model["cables"]:
        for xl in (0.0, 0.5 * model["l_el"]):
            def output(variable, cab=cab, xl=xl):
                return mbs.GetObjectOutputBody(cab, variable, localPosition=[xl, 0, 0], configuration=cfg)
            p = output(exu.OutputVariableType.Position)
            if x_lo <= p[0] <= x_hi:
                yield output, p


def span_forces(mbs, model):
    """Mean axial force (ForceLocal) at element nodes and midpoints in the middle half of the
    upper (tight) and lower (slack) span [N], and the number of points averaged."""
    tight, slack = [], []
    for output, p in span_points(mbs, model):
        f = float(np.ravel(output(exu.OutputVariableType.ForceLocal))[0])
        (tight if p[1] > 0.0 else slack).append(f)
    return tight, slack


def span_speeds(mbs, model):
    """Mean material speed along the span (travel sense: −ẋ on the upper, +ẋ on the lower span)
    [m/s] and mean square transverse speed ẏ² [m²/s²] at the element nodes and midpoints in the
    middle half of the upper (tight) and lower (slack) span."""
    tight, slack = [], []
    for output, p in span_points(mbs, model):
        v = output(exu.OutputVariableType.Velocity)
        if p[1] > 0.0:
            tight.append((-float(v[0]), float(v[1]) ** 2))
        else:
            slack.append((float(v[0]), float(v[1]) ** 2))
    mt, ms = np.mean(tight, axis=0), np.mean(slack, axis=0)
    return float(mt[0]), float(ms[0]), float(mt[1]), float(ms[1])


def wrap_profile(mbs, model, k, cx, segments):
    """Contact along pulley k's wrap in the final state: per segment in contact, the angle of
    the segment midpoint about the pulley centre [rad, travel sense from the top], the normal
    and friction force per metre [N/m] (Exudyn's per-segment force / segment length, positive
    friction = along the pulley's counter-clockwise surface motion), the relative tangential
    velocity belt − pulley [m/s] and the belt's axial force at the midpoint [N]."""
    rows = []
    l_seg = model["l_el"] / segments  # reference length: localPosition
    l_seg_path = l_seg / model["reference_scale"]  # path length: forces per metre
    cfg = exu.ConfigurationType.Current
    for cab, co in zip(model["cables"], model["contacts"][k]):
        f = np.ravel(mbs.GetObjectOutput(co, exu.OutputVariableType.ForceLocal))
        v = np.ravel(mbs.GetObjectOutput(co, exu.OutputVariableType.Coordinates_t))
        for j in range(segments):
            if f[2 * j + 1] == 0.0 and f[2 * j] == 0.0:
                continue
            xl = (j + 0.5) * l_seg
            p = mbs.GetObjectOutputBody(cab, exu.OutputVariableType.Position, localPosition=[xl, 0, 0], configuration=cfg)
            n = float(np.ravel(mbs.GetObjectOutputBody(cab, exu.OutputVariableType.ForceLocal, localPosition=[xl, 0, 0], configuration=cfg))[0])
            ang = math.atan2(p[1], p[0] - cx)  # counter-clockwise from +x
            travel = (ang - math.pi / 2) % (2 * math.pi)  # CCW from the top
            rows.append((travel, -f[2 * j + 1] / l_seg_path, f[2 * j] / l_seg_path, float(v[2 * j]), n))
    rows.sort()
    return [list(r) for r in rows]


def contact_torque(mbs, contacts):
    """Torque of the belt on a pulley about +z [N m] and Σ f_t, Σ f_n over the contact
    segments. ObjectContactFrictionCircleCable2D adds −r·Σ f_t to the circle's left-hand side
    (ComputeODE2LHS: M q̈ + LHS = RHS), so the torque acting on the pulley is +r·Σ f_t (checked:
    on the driven pulley it equals load + damping in the steady state)."""
    ft = fn = 0.0
    for co in contacts:
        f = mbs.GetObjectOutput(co, exu.OutputVariableType.ForceLocal)
        ft += float(np.sum(f[0::2]))
        fn += float(np.sum(f[1::2]))
    return R * ft, ft, fn


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--elements", type=int, default=120, help="ANCF cable elements")
    ap.add_argument("--segments", type=int, default=2, help="contact segments per element (nSegments)")
    ap.add_argument("--h", type=float, default=1e-4, help="time step [s] (stepSize)")
    ap.add_argument("--t-end", type=float, default=2.45, help="end time [s] (tEnd)")
    ap.add_argument("--window", type=float, default=0.45, help="averaging window before t_end [s]")
    ap.add_argument("--force-sample", type=float, default=5e-3, help="sampling of span forces and torques [s]")
    ap.add_argument("--friction", choices=["bristle", "velocity"], default="bristle",
                    help="friction law: the example's bristle (stiffness + velocity penalty) or the 2013 velocity penalty")
    ap.add_argument("--friction-scale", type=float, default=1.0,
                    help="factor on frictionStiffness and frictionVelocityPenalty (>1: towards Coulomb)")
    ap.add_argument("--material", choices=["linear", "svk"], default="linear",
                    help="axial law: Exudyn's EA(|r'|-1-eps0) or St Venant-Kirchhoff (user function)")
    ap.add_argument("--initial-gaps", choices=["example", "geometric"], default="example",
                    help="contact state before the static solve: the example's 'no contact' "
                    "or the laid belt's chord gaps (60 elements need it: the example's start "
                    "does not converge there)")
    ap.add_argument("--gravity", type=float, default=GRAVITY, help="gravity on the belt [m/s2] (0: none)")
    ap.add_argument("--load", type=float, default=LOAD, help="load torque on pulley 1 [N m]")
    ap.add_argument("--damping", type=float, default=DAMP_WHEEL,
                    help="rotational damper of pulley 1 [N m s] (0: none, as flowmbd's fead today)")
    ap.add_argument("--disc-max", type=int, default=3, help="discontinuous iterations (discontinuousIterations)")
    ap.add_argument("--disc-tol", type=float, default=1e-3, help="discontinuous iteration tolerance")
    ap.add_argument("--solver", choices=["trapezoidal", "galpha"], default="trapezoidal",
                    help="TrapezoidalIndex2 (the example) or GeneralizedAlpha (rho_inf 0.9, Exudyn default)")
    ap.add_argument("--reference-scale", type=float, default=1.0,
                    help="diagnostic: element reference length f x path length / n, same physical belt "
                    "(scaled EA, eps0, dEA, rhoA, EI); moves only the contact's sticking-position error")
    ap.add_argument("--rho-inf", type=float, default=0.9,
                    help="spectral radius of --solver galpha (timeIntegration.generalizedAlpha.spectralRadius)")
    ap.add_argument("--threads", type=int, default=1, help="parallel.numberOfThreads")
    ap.add_argument("--wrap-profile", action="store_true",
                    help="print the contact along both wraps in the final state")
    ap.add_argument("--history", type=float, default=0.01, help="interval of the printed speed history [s]")
    a = ap.parse_args()
    if a.elements < 8 or a.segments < 1 or a.h <= 0 or a.t_end <= 0 or not 0 < a.window <= a.t_end:
        ap.error("need elements >= 8, segments >= 1, h > 0, 0 < window <= t_end")
    if a.reference_scale <= 0 or (a.reference_scale != 1.0 and a.material != "linear"):
        ap.error("--reference-scale must be > 0 and needs --material linear")

    t_build = time.perf_counter()
    sc, mbs, model = build(a)

    st = exu.SimulationSettings()
    st.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    st.parallel.numberOfThreads = a.threads
    st.solution.file.write = False
    st.solution.sensors.writePeriod = 1e-3
    st.timeIntegration.endTime = a.t_end
    st.timeIntegration.numberOfSteps = int(round(a.t_end / a.h))
    st.timeIntegration.verboseMode = 0
    st.timeIntegration.stepInformation = 0
    st.timeIntegration.newton.useModifiedNewton = True
    st.timeIntegration.generalizedAlpha.spectralRadius = a.rho_inf
    st.timeIntegration.discontinuous.iterationTolerance = a.disc_tol
    st.timeIntegration.discontinuous.maxIterations = a.disc_max
    st.show.computationTime = False
    st.show.statistics = False
    st.show.globalTimers = False
    # the example's static settings
    st.staticSolver.adaptiveStep = False
    st.staticSolver.loadStepGeometric = True
    st.staticSolver.loadStepGeometricRange = 1e4
    st.staticSolver.numberOfLoadSteps = 10
    st.staticSolver.stabilizerODE2term = 1e5
    st.staticSolver.newton.relativeTolerance = 1e-6
    st.staticSolver.newton.absoluteTolerance = 1e-6
    st.staticSolver.verboseMode = int(__import__("os").environ.get("PG_VERBOSE", "0"))

    # static equilibrium: friction off, velocity drive off, pulley angles and node 0's x held
    mbs.SetObjectParameter(model["vel"], "activeConnector", False)
    for side in model["contacts"]:
        for co in side:
            mbs.SetObjectParameter(co, "frictionCoefficient", 0.0)
            mbs.SetObjectParameter(co, "frictionStiffness", 1e-8)
    t_static = time.perf_counter()
    ok = mbs.SolveStatic(st, updateInitialValues=True)
    t_static = time.perf_counter() - t_static
    if not ok:
        print(json.dumps({"error": "static solve failed"}))
        return 1
    tight0, slack0 = span_forces(mbs, model)
    for side in model["contacts"]:
        for co in side:
            mbs.SetObjectParameter(co, "frictionCoefficient", MU)
            mbs.SetObjectParameter(co, "frictionStiffness", model["friction"]["mu_k"])
    mbs.SetObjectParameter(model["hold_belt"], "activeConnector", False)
    for hold in model["holds"]:
        mbs.SetObjectParameter(hold, "activeConnector", False)
    mbs.SetObjectParameter(model["vel"], "activeConnector", True)

    t_win = a.t_end - a.window
    samples = []  # (t, tight mean, slack mean, torque driven, torque driver, Σft driven, driver constraint)
    state = {"next": t_win}

    def pre_step(mbs_, t):
        if t >= state["next"] - 1e-9:
            state["next"] += a.force_sample
            tight, slack = span_forces(mbs_, model)
            tq1, ft1, _ = contact_torque(mbs_, model["contacts"][1])
            tq0, _, _ = contact_torque(mbs_, model["contacts"][0])
            lam = float(np.ravel(mbs_.GetObjectOutput(model["vel"], exu.OutputVariableType.Force))[0])
            v_t, v_s, vy2_t, vy2_s = span_speeds(mbs_, model)
            samples.append((t, float(np.mean(tight)), float(np.mean(slack)), tq1, tq0, ft1, lam,
                            len(tight), len(slack), v_t, v_s, vy2_t, vy2_s))
        return True

    mbs.SetPreStepUserFunction(pre_step)
    solver = {"trapezoidal": exu.DynamicSolverType.TrapezoidalIndex2,
              "galpha": exu.DynamicSolverType.GeneralizedAlpha}[a.solver]
    t0 = time.perf_counter()
    c0 = time.process_time()
    ok = mbs.SolveDynamic(st, solverType=solver)
    wall = time.perf_counter() - t0
    cpu = time.process_time() - c0
    stats = {}
    try:
        it = mbs.sys["dynamicSolver"].it
        stats = {
            "steps": it.currentStepIndex,
            "newton_iterations": it.newtonStepsCount,
            "jacobians": it.newtonJacobiCount,
            "discontinuous_iterations": it.discontinuousIterationsCount,
            "rejected_modified_newton_steps": it.rejectedModifiedNewtonSteps,
        }
    except Exception:  # noqa: BLE001 (statistics are optional)
        pass

    profiles = {}
    if a.wrap_profile:
        profiles = {"driver": wrap_profile(mbs, model, 0, 0.0, a.segments),
                    "driven": wrap_profile(mbs, model, 1, DIST, a.segments)}
    # pulley speeds (1 ms sensor samples); counter-clockwise positive = travel sense here
    w0 = mbs.GetSensorStoredData(model["sensors"][0])
    w1 = mbs.GetSensorStoredData(model["sensors"][1])
    tt = w1[:, 0]
    sel = tt >= t_win - 1e-9
    om1 = float(np.mean(w1[sel, 3]))
    om0 = float(np.mean(w0[sel, 3]))
    # steadiness: means of the driven speed over the window's thirds
    thirds = [float(np.mean(w1[(tt >= t_win + k * a.window / 3 - 1e-9) & (tt <= t_win + (k + 1) * a.window / 3 + 1e-9), 3]))
              for k in range(3)]
    s = np.array(samples) if samples else np.zeros((0, 13))
    t1, t2 = float(np.mean(s[:, 1])), float(np.mean(s[:, 2]))
    tq1, tq0 = float(np.mean(s[:, 3])), float(np.mean(s[:, 4]))
    applied = a.load + a.damping * om1
    every = max(1, int(round(a.history / 1e-3)))
    out = {
        "code": "exudyn " + exu.__version__,
        "ok": bool(ok),
        "elements": a.elements,
        "segments": a.segments,
        "h": a.h,
        "t_end": a.t_end,
        "window": [t_win, a.t_end],
        "friction": a.friction,
        "friction_scale": a.friction_scale,
        "friction_per_segment": model["friction"],
        "material": a.material,
        "reference_scale": a.reference_scale,
        "initial_gaps": a.initial_gaps,
        "gravity": a.gravity,
        "load": a.load,
        "damping": a.damping,
        "solver": a.solver,
        "rho_inf": a.rho_inf if a.solver == "galpha" else None,
        "threads": a.threads,
        "omega_driver": om0,
        "omega_driven": om1,
        "omega_driven_thirds": thirds,
        "speed_loss_pct": 100.0 * (1.0 - om1 / om0) if om0 != 0.0 else None,
        "static_tight_n": float(np.mean(tight0)),
        "static_slack_n": float(np.mean(slack0)),
        "tension_tight_n": t1,
        "tension_slack_n": t2,
        "tension_meaning": "ObjectANCFCable2D ForceLocal = EA(|r'|-1-eps0) + dEA*d/dt|r'| (the element's own "
        "axial force, linear in engineering strain of the reference length) at element nodes and midpoints "
        "in the middle half of each span; tight = upper span",
        "span_points": [int(np.mean(s[:, 7])), int(np.mean(s[:, 8]))] if len(s) else [0, 0],
        "torque_contact_driven_nm": tq1,
        "torque_contact_driver_nm": tq0,
        "torque_drive_nm": -float(np.mean(s[:, 6])),
        "span_speed_tight_ms": float(np.mean(s[:, 9])),
        "span_speed_slack_ms": float(np.mean(s[:, 10])),
        "span_transverse_rms_ms": [float(np.sqrt(np.mean(s[:, 11]))), float(np.sqrt(np.mean(s[:, 12])))],
        "driver_surface_speed_ms": om0 * R_C,
        "driven_surface_speed_ms": om1 * R_C,
        "span_speed_loss_pct": 100.0 * (1.0 - float(np.mean(s[:, 10])) / float(np.mean(s[:, 9]))),
        "creep_speed_loss_pct": 100.0 * (1.0 - stretch(t2, a.material) / stretch(t1, a.material)),
        "span_torque_nm": (t1 - t2) * R_C,
        "span_torque_r_pulley_nm": (t1 - t2) * R,
        "applied_driven_nm": applied,
        "residual_span_vs_contact_pct": 100.0 * ((t1 - t2) * R_C - tq1) / tq1,
        "residual_contact_vs_applied_pct": 100.0 * (tq1 - applied) / applied,
        "samples": len(s),
        "wall_static_s": t_static,
        "wall_build_s": (t0 - t_build) - t_static,
        "wall_dynamic_s": wall,
        "cpu_dynamic_s": cpu,
        "stats": stats,
        "wrap_profile_columns": ["angle from the top, CCW [rad]", "f_n [N/m]", "f_t [N/m]",
                                 "v_belt - v_pulley [m/s]", "axial force [N]"],
        "wrap_profile": profiles,
        "t": [float(x) for x in tt[::every]],
        "omega_driven_history": [float(x) for x in w1[::every, 3]],
    }
    json.dump(out, sys.stdout)
    sys.stdout.write("\n")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
