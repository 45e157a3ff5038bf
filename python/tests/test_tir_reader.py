"""The MF 6.1 `.tir` of the steady study read by a second, independent reader (issue 38 item 3:
"a `.tir` file that an independent reader parses").

No `.tir` reader is installable from the package registry here (MFeval is MATLAB; OpenTire and
an `mfeval` port are not on PyPI), so this file is that reader: a parser of the ADAMS/MF-Tyre
property-file format (`[SECTION]` headers, `NAME = value` lines, `$` and `!` comments, quoted
strings) and the pure-slip Magic Formula 6.1 equations of Pacejka, *Tire and Vehicle Dynamics*,
3rd ed., §4.3.2 (4.E1–4.E49), written here from the book with every load, camber, pressure and
turn-slip term kept, and evaluated with the file's coefficients. It shares no code with
`tire::tir` (the writer) or `tire::magic_formula` (the fit). References: the fitted values the
study reports (the same curves evaluated by the fit) and the simulated points within the
fit's own stated error.
"""

import math

import numpy as np
import pytest

import flowmbd

# the slip angles of apps/tire/examples/small-tire-steady.toml: adhesion to sliding on the
# small tire; three torques so that Fx(kappa) is fitted as well
SLIP = [-1.0, -0.4, -0.1, 0.1, 0.2, 0.4, 1.0]
TORQUES = [-500.0, 250.0, 500.0]


def read_tir(text):
    """{SECTION: {NAME: float or str}} of a property file."""
    out, section = {}, None
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("$", 1)[0].split("!", 1)[0].strip()
        if not line:
            continue
        if line.startswith("[") and line.endswith("]"):
            section = line[1:-1].strip().upper()
            out.setdefault(section, {})
            continue
        name, sep, value = line.partition("=")
        assert sep and section, f"line {n}: not 'NAME = value' inside a section: {raw!r}"
        value = value.strip()
        if value.startswith("'") or value.startswith('"'):
            out[section][name.strip().upper()] = value.strip("'\"")
        else:
            out[section][name.strip().upper()] = float(value)
    return out


def mf61_pure_slip(p, fz, alpha, kappa, gamma=0.0, pressure=None):
    """(Fx0, Fy0, Mz0) of MF 6.1 pure slip (Pacejka 3rd ed. 4.E1-4.E49, no turn slip: zeta = 1)
    in the W-axis system of the file (alpha: its slip angle, tan alpha = V_y/|V_x|)."""
    g = lambda s, k: p.get(s, {}).get(k, 0.0)  # noqa: E731  (absent coefficients are zero)
    lat, lon, ali = "LATERAL_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS"
    sc = lambda k: p["SCALING_COEFFICIENTS"].get(k, 1.0)  # noqa: E731
    fz0 = p["VERTICAL"]["FNOMIN"]
    r0 = p["DIMENSION"]["UNLOADED_RADIUS"]
    p0 = p["OPERATING_CONDITIONS"]["NOMPRES"]
    pi = p["OPERATING_CONDITIONS"]["INFLPRES"] if pressure is None else pressure
    eps = 1e-6
    fz0p = fz0 * sc("LFZO")  # 4.E1
    dfz = (fz - fz0p) / fz0p  # 4.E2a
    dpi = (pi - p0) / p0  # 4.E2b
    a_star = math.tan(alpha)  # 4.E3 (V_cx > 0)
    g_star = math.sin(gamma)  # 4.E4
    # longitudinal 4.E9-4.E18
    shx = (g(lon, "PHX1") + g(lon, "PHX2") * dfz) * sc("LHX")
    kx = kappa + shx
    cx = g(lon, "PCX1") * sc("LCX")
    mux = (g(lon, "PDX1") + g(lon, "PDX2") * dfz) * (1 + g(lon, "PPX3") * dpi + g(lon, "PPX4") * dpi**2) \
        * (1 - g(lon, "PDX3") * gamma**2) * sc("LMUX")
    dx = mux * fz
    ex = (g(lon, "PEX1") + g(lon, "PEX2") * dfz + g(lon, "PEX3") * dfz**2) \
        * (1 - g(lon, "PEX4") * np.sign(kx)) * sc("LEX")
    kxk = fz * (g(lon, "PKX1") + g(lon, "PKX2") * dfz) * math.exp(g(lon, "PKX3") * dfz) \
        * (1 + g(lon, "PPX1") * dpi + g(lon, "PPX2") * dpi**2) * sc("LKX")
    bx = kxk / (cx * dx + eps) if cx * dx else 0.0
    svx = fz * (g(lon, "PVX1") + g(lon, "PVX2") * dfz) * sc("LVX") * sc("LMUX")
    fx0 = dx * math.sin(cx * math.atan(bx * kx - ex * (bx * kx - math.atan(bx * kx)))) + svx
    # lateral 4.E19-4.E30
    kya = g(lat, "PKY1") * fz0p * (1 + g(lat, "PPY1") * dpi) * (1 - g(lat, "PKY3") * abs(g_star)) \
        * math.sin(g(lat, "PKY4") * math.atan(fz / ((g(lat, "PKY2") + g(lat, "PKY5") * g_star**2)
                                                   * (1 + g(lat, "PPY2") * dpi) * fz0p))) * sc("LKY")
    svyg = fz * (g(lat, "PVY3") + g(lat, "PVY4") * dfz) * g_star * sc("LKYC") * sc("LMUY")
    kyg0 = fz * (g(lat, "PKY6") + g(lat, "PKY7") * dfz) * (1 + g(lat, "PPY5") * dpi) * sc("LKYC")
    shy = (g(lat, "PHY1") + g(lat, "PHY2") * dfz) * sc("LHY")
    if g_star:
        shy += (kyg0 * g_star - svyg) / (kya + eps)
    ay = a_star + shy
    cy = g(lat, "PCY1") * sc("LCY")
    muy = (g(lat, "PDY1") + g(lat, "PDY2") * dfz) * (1 + g(lat, "PPY3") * dpi + g(lat, "PPY4") * dpi**2) \
        * (1 - g(lat, "PDY3") * g_star**2) * sc("LMUY")
    dy = muy * fz
    ey = (g(lat, "PEY1") + g(lat, "PEY2") * dfz) * (1 + g(lat, "PEY5") * g_star**2
                                                    - (g(lat, "PEY3") + g(lat, "PEY4") * g_star) * np.sign(ay)) * sc("LEY")
    by = kya / (cy * dy + eps)
    svy = fz * (g(lat, "PVY1") + g(lat, "PVY2") * dfz) * sc("LVY") * sc("LMUY") + svyg
    fy0 = dy * math.sin(cy * math.atan(by * ay - ey * (by * ay - math.atan(by * ay)))) + svy
    # aligning 4.E31-4.E49 (pneumatic trail and residual moment)
    sht = g(ali, "QHZ1") + g(ali, "QHZ2") * dfz + (g(ali, "QHZ3") + g(ali, "QHZ4") * dfz) * g_star
    at = a_star + sht
    bt = (g(ali, "QBZ1") + g(ali, "QBZ2") * dfz + g(ali, "QBZ3") * dfz**2) \
        * (1 + g(ali, "QBZ5") * abs(g_star) + g(ali, "QBZ6") * g_star**2) * sc("LKY") / sc("LMUY")
    ct = g(ali, "QCZ1")
    dt0 = fz * (r0 / fz0p) * (g(ali, "QDZ1") + g(ali, "QDZ2") * dfz) * (1 - g(ali, "PPZ1") * dpi) * sc("LTR")
    dt = dt0 * (1 + g(ali, "QDZ3") * abs(g_star) + g(ali, "QDZ4") * g_star**2)
    et = (g(ali, "QEZ1") + g(ali, "QEZ2") * dfz + g(ali, "QEZ3") * dfz**2) \
        * (1 + (g(ali, "QEZ4") + g(ali, "QEZ5") * g_star) * (2 / math.pi) * math.atan(bt * ct * at))
    cos_a = math.cos(alpha)  # cos'alpha = V_cx / (V_c + eps_v)
    t0 = dt * math.cos(ct * math.atan(bt * at - et * (bt * at - math.atan(bt * at)))) * cos_a
    # F'y0 of 4.E48: Fy0 at zero camber
    fy0p = fy0 if not g_star else mf61_pure_slip(p, fz, alpha, kappa, 0.0, pressure)[1]
    mzp = -t0 * fy0p
    shf = shy + svy / (kya + eps)
    ar = a_star + shf
    br = (g(ali, "QBZ9") * sc("LKY") / sc("LMUY") + g(ali, "QBZ10") * by * cy)
    dr = fz * r0 * ((g(ali, "QDZ6") + g(ali, "QDZ7") * dfz) * sc("LRES")
                    + ((g(ali, "QDZ8") + g(ali, "QDZ9") * dfz) * (1 + g(ali, "PPZ2") * dpi)
                       + (g(ali, "QDZ10") + g(ali, "QDZ11") * dfz) * abs(g_star)) * g_star * sc("LKZC")) \
        * sc("LMUY") * cos_a
    mzr = dr * math.cos(math.atan(br * ar)) * cos_a
    return fx0, fy0, mzp + mzr


@pytest.fixture(scope="module")
def steady(reduced):
    return flowmbd.tire.steady(config={"slip_angles_deg": SLIP, "drive_torques_n_m": TORQUES,
                                       "point_time": 0.15, "average_time": 0.03}, tire=reduced)


def test_the_tir_parses_as_an_mf61_property_file(steady):
    tir = steady["tir_text"]
    assert isinstance(tir, str)
    p = read_tir(tir)
    for s in ["MDI_HEADER", "UNITS", "MODEL", "DIMENSION", "OPERATING_CONDITIONS", "VERTICAL",
              "SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS", "LATERAL_COEFFICIENTS",
              "ALIGNING_COEFFICIENTS"]:
        assert s in p, s
    assert p["MDI_HEADER"]["FILE_TYPE"] == "tir"
    assert p["MODEL"]["FITTYP"] == 61
    assert p["UNITS"]["FORCE"] == "newton" and p["UNITS"]["ANGLE"] == "radians"
    assert p["VERTICAL"]["FNOMIN"] == pytest.approx(steady["load_n"], rel=1e-12)
    # W-axis sign (MF-Tyre): a free tire's side force falls with the W-axis slip angle
    assert p["LATERAL_COEFFICIENTS"]["PKY1"] < 0


def test_mf61_from_the_tir_reproduces_the_fit_and_the_simulation(steady):
    p = read_tir(steady["tir_text"])
    m = steady["magic_formula"]
    fz = steady["load_n"]
    err_y = m["fit"]["lateral"]["fy_error"]
    err_z = m["fit"]["lateral"]["mz_error"]
    pts = {round(a, 9): (fy, mz) for a, fy, mz in zip(steady["slip_angle_deg"], steady["fy_n"],
                                                       steady["mz_n_m"])}
    for a, fy_fit, mz_fit in zip(m["slip_angle_deg"], m["fy_fit_n"], m["mz_fit_n_m"]):
        # the file's W-axis slip angle is minus Pacejka's of the study (tire::tir docs, and
        # Pacejka 3rd ed. §4.3.1: alpha_W = -alpha in the ISO axes)
        _, fy, mz = mf61_pure_slip(p, fz, -math.radians(a), 0.0)
        # reference 1: the study's own evaluation of its fit (tire::magic_formula)
        assert fy == pytest.approx(fy_fit, rel=1e-9, abs=1e-6 * err_y["peak"]), a
        assert mz == pytest.approx(mz_fit, rel=1e-9, abs=1e-6 * err_z["peak"]), a
        # reference 2: the simulated points, within the fit's own stated largest error plus
        # the file's rounding (reference 1's tolerance: the reader's curve may differ from the
        # fit's by 1e-6 of the peak, so |fy - sim| <= fit error + that)
        if round(a, 9) in pts:
            sim_fy, sim_mz = pts[round(a, 9)]
            assert abs(fy - sim_fy) <= err_y["max"] * (1 + 1e-9) + 1e-6 * err_y["peak"], a
            assert abs(mz - sim_mz) <= err_z["max"] * (1 + 1e-9) + 1e-6 * err_z["peak"], a
    lon = m["fit"]["longitudinal"]
    assert lon is not None, m.get("warnings")
    for k, fx_fit in zip(m["kappa"], m["fx_fit_n"]):
        fx, _, _ = mf61_pure_slip(p, fz, 0.0, k)
        assert fx == pytest.approx(fx_fit, rel=1e-9, abs=1e-6 * lon["fx_error"]["peak"]), k
