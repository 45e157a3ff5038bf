"""Cleat test speed sweep over three tire variants (inflation pressure 32, 38 and 44 psi), on
Dask, written to tire_cleat_speed_sweep.png: the dominant vertical spindle-force frequency and
the force fluctuation after the cleat against speed (Ribaric §8.3, Figs. 8-7 and 8-8).

Each variant is reduced once (Ribaric §8.2), on a worker, and the reduced tire is reused by every
speed of that variant: Dask ships the ``ReducedTire`` (it pickles) to the workers that need it.
The full-size truck tire takes about 30 s and 2 GB per reduction; ``--coarse`` uses the small
tire of the tests (seconds) for a quick look.

    python python/examples/tire_cleat_speed_sweep.py [--coarse] [--speeds 20,40,60]
        [--out DIR] [--scheduler ADDRESS]
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import flowmbd  # noqa: E402

PSI = 6894.757  # [Pa]
VARIANTS = {f"{p} psi": {"inflation_pressure": p * PSI} for p in (32, 38, 44)}
# the small generated tire of the tests (isotropic tread, 33 contact nodes)
COARSE = {
    "generator": {"circumferential_divisions": 96, "section_divisions": 8,
                  "thickness_divisions": 1, "bead_elements": 1, "patch_half_angle_deg": 20.0,
                  "tread": {"young": 150e6, "poisson": 0.45, "density": 1500.0},
                  "carcass": {"modulus": 0.0}},
    "reduction": {"contact_nodes": 33, "free_modes": 50},
}


def tire_config(variant, coarse):
    base = COARSE if coarse else {"generator": {}, "reduction": {}}
    return {"generator": {**base["generator"], **VARIANTS[variant]},
            "reduction": dict(base["reduction"])}


def point(variant, speed_kmh, tire, record_time):
    """One cleat run with the variant's reduced tire."""
    # one tire per Dask worker process: no product worker thread per run (`threads`)
    r = flowmbd.tire.cleat(speed_kmh=speed_kmh, tire=tire,
                           config={"rig": {"record_time": record_time,
                                           "rolling": {"threads": 1}}})
    return {"fy_peak_hz": r["fy_peak_hz"], "fx_peak_hz": r["fx_peak_hz"], "fy_rms": r["fy_rms"],
            "fx_rms": r["fx_rms"], "loaded_vertical_mode_hz": r["loaded_vertical_mode_hz"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=".", help="output folder")
    ap.add_argument("--coarse", action="store_true", help="the small test tire (fast)")
    ap.add_argument("--speeds", default="20,30,40,50,60,70,80,90,100", help="speeds [km/h]")
    ap.add_argument("--record-time", type=float, default=0.3, help="record after the hit [s]")
    ap.add_argument("--scheduler", default=None,
                    help="Dask scheduler address (default: a 2-worker LocalCluster)")
    args = ap.parse_args()
    speeds = [float(v) for v in args.speeds.split(",")]

    from dask.distributed import Client, LocalCluster

    cluster = None
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0")
        client = Client(cluster)
    try:
        # reduce each variant once, on the workers; the futures hold the ReducedTire objects
        tires = {v: client.submit(flowmbd.tire.reduce, tire_config(v, args.coarse), pure=False)
                 for v in VARIANTS}
        grid = [{"variant": v, "speed_kmh": s, "tire": tires[v], "record_time": args.record_time}
                for v in VARIANTS for s in speeds]
        df = flowmbd.sweep(point, grid, client=client).drop(columns="tire")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for variant, g in df[df["error"].isna()].groupby("variant", sort=False):
        line, = a1.plot(g["speed_kmh"], g["fy_peak_hz"], "o-", label=f"{variant}: Fy peak")
        a1.plot(g["speed_kmh"], g["loaded_vertical_mode_hz"], "--", color=line.get_color(),
                label=f"{variant}: loaded vertical mode")
        a2.plot(g["speed_kmh"], g["fy_rms"], "o-", color=line.get_color(), label=variant)
    a1.set_xlabel("speed [km/h]")
    a1.set_ylabel("frequency [Hz]")
    a1.legend(fontsize=7)
    a2.set_xlabel("speed [km/h]")
    a2.set_ylabel("Fy fluctuation after the cleat (rms) [N]")
    a2.legend(fontsize=7)
    fig.tight_layout()
    out = pathlib.Path(args.out) / "tire_cleat_speed_sweep.png"
    fig.savefig(out, dpi=120)
    print(df.to_string())
    print(f"wrote {out}")
    failed = df["error"].notna().sum()
    if failed:
        print(f"{failed} point(s) failed: see the error column")


if __name__ == "__main__":
    main()
