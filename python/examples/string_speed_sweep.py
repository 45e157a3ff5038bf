"""Travelling-string frequencies over axial speed for three string variants (tension ×
density), on Dask, written to string_speed_sweep.png: the flowing-material model (4.20)
against the Galerkin model (4.29); each variant's frequencies fall to zero at its critical
speed c = √(T/ρA) (Ribaric §4.2.3).

    python python/examples/string_speed_sweep.py [--out DIR] [--scheduler ADDRESS]
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import _example  # noqa: E402
import flowmbd  # noqa: E402

VARIANTS = {
    "steel, T = 1000 N": {"tension": 1000.0, "density": 7850.0},
    "steel, T = 2000 N": {"tension": 2000.0, "density": 7850.0},
    "polymer, T = 1000 N": {"tension": 1000.0, "density": 1200.0},
}


def point(variant, fraction):
    """Lowest two frequencies at `fraction` of the variant's critical speed."""
    string = dict(VARIANTS[variant], length=1.0, area=7.854e-5)
    c = np.sqrt(string["tension"] / (string["density"] * string["area"]))
    r = flowmbd.string.modes(speed=fraction * c, nodes=60, modes=20, config={"string": string})
    return {"speed": fraction * c, "f1_hz": r["flowing_hz"][0], "f2_hz": r["flowing_hz"][1],
            "f1_galerkin_hz": r["analytical_hz"][0]}


def main():
    args = _example.arguments(__doc__)
    client = _example.client(args.scheduler)
    grid = {"variant": list(VARIANTS), "fraction": list(np.linspace(0.0, 0.95, 12))}
    df = flowmbd.sweep(point, grid, client=client)
    fig, ax = plt.subplots(figsize=(6, 4))
    for variant, g in df[df["error"].isna()].groupby("variant", sort=False):
        line, = ax.plot(g["speed"], g["f1_hz"], "o-", label=f"{variant}, flowing (4.20)")
        ax.plot(g["speed"], g["f1_galerkin_hz"], "--", color=line.get_color(), label="Galerkin (4.29)")
    ax.set_xlabel("axial speed [m/s]")
    ax.set_ylabel("first damped frequency [Hz]")
    ax.legend(fontsize=7)
    _example.save(fig, args.out, "string_speed_sweep.png", df)


if __name__ == "__main__":
    main()
