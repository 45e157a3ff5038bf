"""flowmbd: flexible multibody dynamics of belts, beams, strings and tires.

The Python API over the flowmbd Rust crates (the same engine, configuration keys, checks and
results as the ``flowmbd-*`` command-line studies):

- :mod:`flowmbd.belt`: ``speed_loss`` (Ribaric §6.4–6.5), ``ancf`` and ``plate`` (Kerkkänen
  ch. 3–4), ``fead``, ``design``, ``wave`` and ``demo``;
- :mod:`flowmbd.beam`: the ANCF beam studies of Kerkkänen §2.4: ``simply_supported``
  (Tables 2.1/2.2), ``cantilever`` (Tables 2.3/2.4), ``pendulum`` (Figs 2.6/2.7), ``spinning``
  (Figs 2.10/2.11) and ``ground_contact``;
- :mod:`flowmbd.string`: ``modes`` (Ribaric §4.2.3), ``sweep``, ``simulate`` and ``wrap`` (ch. 4);
- :mod:`flowmbd.tire`: the reduced FE tire (generate, import, ``reduce`` once into a picklable
  ``ReducedTire``) and its studies ``cleat``, ``steady``, ``sweep``, ``dips``, ``pressure``,
  ``modes`` and ``rotating_modes`` (Ribaric ch. 7–8);
- :mod:`flowmbd.reduce`: ``modes``, ``craig_bampton`` and ``eitelberg`` of scipy.sparse
  matrices (Lin ch. 6), and the studies ``lin_beam`` (Lin ch. 6–8, Appendix A beam) and
  ``lin_slab`` (Lin §7.2, Appendix B slab) and ``tire_mesh`` (the generated tire's K and M);
- :func:`flowmbd.sweep`: parameter sweeps on Dask distributed.

Studies take their configuration as a dict with the keys of the TOML file (``--print-config``
of the CLI), read deeply over the defaults like a partial TOML file (``{"drive": {"tension":
300.0}}`` changes one number of the default drive), and return the content of the CLI's ``summary.json`` as a :class:`Result`: a dict with numpy
arrays for number series, whose ``to_dataframe()`` gives its per-point records as a pandas
DataFrame; with ``series=True`` a study also returns the series its CLI writes as CSV files
(under the file's name, a dict of numpy columns). Bad input raises ``ValueError`` (the CLI's message); a numerical failure
raises :class:`NumericalError` with the partial results attached. Long runs release the GIL.
"""

from importlib.metadata import PackageNotFoundError, version

from . import beam, belt, reduce, string, tire
from ._errors import NumericalError
from ._results import Result
from .sweep import points, sweep

try:
    #: The installed package's version (the workspace's, set by maturin from Cargo.toml).
    __version__ = version("flowmbd")
except PackageNotFoundError:  # imported from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["beam", "belt", "string", "tire", "reduce", "sweep", "points", "NumericalError", "Result", "__version__"]
