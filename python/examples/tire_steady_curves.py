"""Steady-state characteristics of the small tire on a flat road (issue 38): the longitudinal
force against the prescribed longitudinal slip, F_x(kappa), and the side force and aligning
moment against the slip angle, F_y(alpha) and M_z(alpha) (ISO 8855 wheel frame), from
``flowmbd.tire.steady``.

The configuration is ``apps/tire/examples/small-tire-steady.toml`` (the coarse tire of the tests,
seven slip angles, one drive torque, eight prescribed slips, 0.15 s per point) as a dict; each
``slip_ratios`` point holds the spin at ``(1 + kappa)`` times the free-rolling spin, so F_x(kappa)
is obtained through and beyond its peak. About 15 s.

Writes ``fx_kappa.csv``, ``fy_mz_alpha.csv`` and, when matplotlib is installed,
``tire_steady_curves.png`` into ``--out`` (default ``out/tire/steady-curves``, as the CLI's
``out/<app>/<study>``).

    python python/examples/tire_steady_curves.py [--out DIR]
"""

import argparse
import csv
import pathlib

import flowmbd

# apps/tire/examples/small-tire-steady.toml as a dict (its [tire] without ``reduced_file``,
# which the Python package ignores: it keeps the reduced tire as an object)
CONFIG = {
    "slip_angles_deg": [-1.0, -0.4, -0.1, 0.1, 0.2, 0.4, 1.0],
    "drive_torques_n_m": [500.0],
    "slip_ratios": [-0.01, -0.004, -0.002, -0.001, 0.001, 0.002, 0.004, 0.01],
    "point_time": 0.15,
    "average_time": 0.03,
    "tire": {
        "generator": {
            "circumferential_divisions": 96,
            "section_divisions": 8,
            "thickness_divisions": 1,
            "bead_elements": 1,
            "patch_half_angle_deg": 20.0,
            "tread": {"young": 150e6, "poisson": 0.45, "density": 1500.0},
            "carcass": {"modulus": 0.0},
        },
        "reduction": {"contact_nodes": 33, "free_modes": 50},
    },
}
# prescribed longitudinal slips [-]: braking and driving, through the peak of this stiff tire
SLIP_RATIOS = CONFIG["slip_ratios"]


def curves(summary):
    """The three curves of a steady summary: ``{"fx_kappa": rows, "fy_mz_alpha": rows}`` with
    rows ``(kappa [-], Fx [N], spin torque [N m])`` over the prescribed slips and
    ``(alpha [deg], Fy [N], Mz [N m])`` over the slip angles, each sorted by its abscissa."""
    fx = sorted(zip(summary["prescribed_kappa"], summary["prescribed_fx_n"],
                    summary["prescribed_spin_torque_n_m"]))
    lateral = sorted(zip(summary["slip_angle_deg"], summary["fy_n"], summary["mz_n_m"]))
    return {"fx_kappa": fx, "fy_mz_alpha": lateral}


def write_csv(out_dir, c):
    """Write the curves ``c`` as ``fx_kappa.csv`` and ``fy_mz_alpha.csv``; returns the paths."""
    header = {"fx_kappa": ["kappa_ratio", "fx_N", "spin_torque_N_m"],
              "fy_mz_alpha": ["slip_angle_deg", "fy_N", "mz_N_m"]}
    paths = []
    for name, rows in c.items():
        path = pathlib.Path(out_dir) / f"{name}.csv"
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header[name])
            w.writerows(rows)
        paths.append(path)
    return paths


def plot(out_dir, c):
    """Plot F_x(kappa), F_y(alpha) and M_z(alpha) side by side into
    ``tire_steady_curves.png``; returns its path, or ``None`` without matplotlib."""
    try:
        import matplotlib
    except ImportError:
        return None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    k, fx, _ = zip(*c["fx_kappa"])
    a, fy, mz = zip(*c["fy_mz_alpha"])
    for axis, x, y, xl, yl in ((ax[0], k, fx, "kappa [-]", "Fx [N]"),
                               (ax[1], a, fy, "alpha [deg]", "Fy [N]"),
                               (ax[2], a, mz, "alpha [deg]", "Mz [N m]")):
        axis.plot(x, y, "o-")
        axis.set_xlabel(xl)
        axis.set_ylabel(yl)
        axis.grid(True)
    ax[0].set_title("prescribed slip")
    ax[1].set_title("side force")
    ax[2].set_title("aligning moment")
    fig.tight_layout()
    path = pathlib.Path(out_dir) / "tire_steady_curves.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def main(argv=None):
    """Run the study, write the CSV files and the plot; returns ``(summary, paths)``."""
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out/tire/steady-curves", help="output folder")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    summary = flowmbd.tire.steady(CONFIG)
    c = curves(summary)
    paths = write_csv(out, c)
    png = plot(out, c)
    if png is not None:
        paths.append(png)
    print(f"cornering stiffness {summary['cornering_stiffness_n_per_rad']:.4g} N/rad, "
          f"slip stiffness {summary['slip_stiffness_n']:.4g} N")
    for p in paths:
        print(f"wrote {p}")
    return summary, paths


if __name__ == "__main__":
    main()
