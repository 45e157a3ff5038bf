"""Belt speed-loss map: Δω over load torque × driver speed (Ribaric Table 6-1 drive, flowing
model), one Dask task per point, written to belt_torque_speed_map.png.

    python python/examples/belt_torque_speed_map.py [--out DIR] [--scheduler ADDRESS]
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import _example  # noqa: E402
import flowmbd  # noqa: E402


def point(omega, torque):
    """One operating point: steady speed loss and Bechtel's line (6.3)."""
    r = flowmbd.belt.speed_loss(omega=omega, torques=[torque])
    return {"delta_omega": r["points"][0]["delta_omega"], "bechtel": r["analytical"][0]}


def main():
    args = _example.arguments(__doc__)
    client = _example.client(args.scheduler)
    grid = {"omega": [22.6, 42.7, 62.8], "torque": [0.0, 2.5, 5.0, 7.5, 10.0]}
    df = flowmbd.sweep(point, grid, client=client)
    failed = df[df["error"].notna()]
    if len(failed):
        print("failed points:\n", failed[["omega", "torque", "error"]])
    fig, ax = plt.subplots(figsize=(6, 4))
    for omega, g in df[df["error"].isna()].groupby("omega"):
        line, = ax.plot(g["torque"], g["delta_omega"], "o-", label=f"flowing, ω₁ = {omega} rad/s")
        ax.plot(g["torque"], g["bechtel"], "--", color=line.get_color(), label=f"Bechtel (6.3), {omega} rad/s")
    ax.set_xlabel("load torque [N m]")
    ax.set_ylabel("Δω = ω₁ − ω₂ [rad/s]")
    ax.set_title("Belt speed loss, Ribaric Table 6-1")
    ax.legend(fontsize=7)
    _example.save(fig, args.out, "belt_torque_speed_map.png", df)


if __name__ == "__main__":
    main()
