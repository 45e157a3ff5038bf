"""What the Dask examples share: their command line (``--out``, ``--scheduler``), the Dask
client and writing the plot with the table of results."""

import argparse
import pathlib


def arguments(doc):
    """The parsed ``--out DIR`` and ``--scheduler ADDRESS`` of an example described by ``doc``."""
    ap = argparse.ArgumentParser(description=doc)
    ap.add_argument("--out", default=".", help="output folder")
    ap.add_argument("--scheduler", default=None, help="Dask scheduler address (default: LocalCluster)")
    return ap.parse_args()


def client(scheduler):
    """A Dask client of the scheduler at ``scheduler``, or ``None`` without one
    (``flowmbd.sweep`` then starts a LocalCluster)."""
    if not scheduler:
        return None
    from dask.distributed import Client

    return Client(scheduler)


def save(fig, out_dir, name, df):
    """Write ``fig`` to ``out_dir/name`` and print the results ``df`` and the file written."""
    out = pathlib.Path(out_dir) / name
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(df)
    print(f"wrote {out}")
