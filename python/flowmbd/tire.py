"""The reduced FE truck tire with flowing material (Ribaric ch. 7–8; ``flowmbd-tire``).

Make the tire once and reuse it: :func:`reduce` returns a :class:`ReducedTire` (the reduction of
Ribaric §8.2 of the generated or imported FE tire) that every tire study here takes as
``tire=``, so that a speed sweep reduces each tire variant once. A ``ReducedTire`` pickles (its
versioned JSON form, bit-identical), so it can be shipped to Dask workers, and saves to / loads
from the file that ``flowmbd-tire`` uses as ``tire.reduced_file``.

- :func:`generate`, :func:`import_model`: the FE tire (``M``, ``K`` as scipy.sparse matrices,
  node coordinates, rim and candidate patch node sets), e.g. for :mod:`flowmbd.reduce`;
- :func:`reduce`: the reduced tire;
- :func:`cleat`: the cleat test of §8.3 at one speed (``flowmbd-tire cleat``);
- :func:`steady`: steady-state side force, aligning moment and longitudinal force
  (``flowmbd-tire steady``);
- :func:`rotating_modes`: complex modes of the rolling tire in the ground frame, Campbell
  diagram (``flowmbd-tire rotating-modes``);
- :func:`sweep`: the cleat test over speeds, Ribaric Figs. 8-7, 8-8, 8-14
  (``flowmbd-tire sweep``);
- :func:`dips`: the speed dips of the cleat test, predicted and measured
  (``flowmbd-tire dips``);
- :func:`pressure`: the preloaded contact patch on drum and road, Fig. 8-12
  (``flowmbd-tire pressure``);
- :func:`modes`: full FE against reduced frequencies, and the loaded modes
  (``flowmbd-tire modes``);
- :class:`Simulation`: the tire rolling on the cleat rig, stepped in time (the cleat test's
  start and step).

Series that the CLI writes as CSV files come back with ``series=True``: under the CSV file's
name without ``.csv`` (e.g. ``"rotating_modes"``), a dict of its columns (the CSV header) as
numpy arrays.

Configurations are dicts with the keys of the TOML files (``flowmbd-tire cleat
--print-config``): the ``tire`` table has ``generator`` (or ``import``) and ``reduction``.
"""

from __future__ import annotations

from typing import Any, Mapping, Optional, Sequence

import numpy as np
import scipy.sparse as sp

from . import _args, _native
from ._stepping import Native, Stepping
from ._results import Result, config_json, from_json, with_series

ReducedTire = _native.ReducedTire

#: Columns of the force history (``forces.csv`` of ``flowmbd-tire cleat``).
FORCE_COLUMNS = tuple(_native.CLEAT_FORCE_COLUMNS)

#: Columns of the amplitude spectra (``spectra.csv`` of ``flowmbd-tire cleat``).
SPECTRUM_COLUMNS = tuple(_native.CLEAT_SPECTRUM_COLUMNS)


def _reduced_tire_from_bytes(data: bytes) -> "ReducedTire":
    """Unpickle a :class:`ReducedTire` (its versioned JSON text as UTF-8 bytes)."""
    return ReducedTire.from_json(bytes(data).decode("utf-8"))


def _fe_dict(out) -> dict:
    nodes, (rows, cols, vals), mass, rim, patch = out
    n = mass.shape[0]
    K = sp.csc_matrix((vals, (rows.astype(np.int64), cols.astype(np.int64))), shape=(n, n))
    return {
        "nodes": nodes,
        "K": K,
        "M": sp.diags(mass, 0, format="csc"),
        "mass": mass,
        "rim_nodes": rim.astype(np.int64),
        "patch_nodes": patch.astype(np.int64),
    }


def generate(config: Optional[Mapping[str, Any]] = None) -> dict:
    """Generate the FE tire (fe-model's truck-tire generator: 295/80 R22.5 at 38 psi by default)
    with the inflation prestress in ``K`` (Ribaric §8.1) and the lumped mass (§7.2): the model
    :func:`reduce` starts from. ``flowmbd-reduce tire-mesh`` is :func:`flowmbd.reduce.tire_mesh`
    (same mesh and ``K``, but the consistent mass by default, the geometric stiffness
    switchable and every node set).

    Parameters
    ----------
    config : the ``[tire.generator]`` table as a dict (missing keys keep their defaults).

    Returns
    -------
    dict
        ``nodes`` (n × 3, wheel frame [m]: x forward, y the wheel axis, z up), ``K``
        (scipy.sparse 3n × 3n [N/m], node-major DOFs x, y, z), ``M`` (diagonal scipy.sparse
        [kg]) and ``mass`` (its diagonal), ``rim_nodes`` and ``patch_nodes`` (0-based node
        indices).

    Raises
    ------
    ValueError
        Bad input (the CLI's ``tire.generator.…: reason`` message).
    """
    return _fe_dict(_native.tire_generate(config_json(config)))


def import_model(config: Mapping[str, Any]) -> dict:
    """Import an FE tire from files (``[tire.import]``: ``format`` = ``"abaqus"`` for ABAQUS
    ``*MATRIX GENERATE`` output or ``"matrix_market"``, ``stiffness``, ``mass``, ``nodes``,
    ``rim_nodes``, ``patch_nodes``; see the README, "Imported tire"). A consistent mass is
    lumped by row sums. Returns the dict of :func:`generate`.

    Raises
    ------
    ValueError
        A missing, unreadable or malformed file (``tire.import.<field>: …``, the CLI's message).
    """
    if not isinstance(config, Mapping):
        raise ValueError(f"tire.import: expected a dict with the TOML keys, got {type(config).__name__}")
    return _fe_dict(_native.tire_import(config_json(config)))


def reduce(config: Optional[Mapping[str, Any]] = None) -> "ReducedTire":
    """Reduce the tire (Ribaric §8.2: contact-node modes, free-node modes and static modes,
    circumferential mode-shape derivatives) once, for reuse in the studies.

    Parameters
    ----------
    config : the ``[tire]`` table as a dict: ``generator`` (the generated tire, default the
        truck tire) or ``import`` (an imported tire, see :func:`import_model`), and
        ``reduction`` (``contact_nodes``, 95, and ``free_modes``, 50, by default). Its
        ``reduced_file`` is not used: the returned object is the cache (``.save(path)`` writes
        the file ``flowmbd-tire`` reuses).

    Returns
    -------
    ReducedTire
        Matrices ``m``, ``k``, ``g1``, ``g2``, ``k1``, ``kr``, ``kr1``, ``kt``, ``kt1``,
        ``tc``, ``tc_theta``, ``p_e``, ``p_e1``, ``p_e2`` and vectors ``m_theta``, ``c_s`` as
        numpy arrays; ``n_contact``, ``n_free_modes``, ``n_z``, ``dof``, ``contact_nodes``,
        ``contact_positions``, ``free_mode_hz``, ``contact_mode_hz``, ``tire_mass``,
        ``rim_mass``, ``rim_spin_inertia``, ``outer_radius``, ``source``, ``code_version``;
        ``frequencies_hz()``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``tire.…: reason`` message).
    flowmbd.NumericalError
        An eigen solve or factorisation failed.
    """
    return _native.tire_reduce(config_json(config))


def cleat(
    speed_kmh: Optional[float] = 60.0,
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    series: bool = False,
) -> Result:
    """The cleat test of Ribaric §8.3 at one speed (``flowmbd-tire cleat --speed``): the
    preloaded tire rolls over a semicircular cleat on the drum (or road) and the spindle forces
    are recorded.

    Parameters
    ----------
    speed_kmh : speed [km/h] (replaces ``config["rig"]["speed_kmh"]``; ``None`` keeps it).
    config : dict with the keys of ``flowmbd-tire cleat --print-config`` (``tire``, ``rig``;
        ``vtk_interval`` and ``vtk_tire_interval`` are accepted and not used).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent): reduce once, run many.
    series : also return the force history (``"forces"``: the columns of ``forces.csv``,
        :data:`FORCE_COLUMNS`, numpy arrays) and the amplitude spectra (``"spectra"``:
        :data:`SPECTRUM_COLUMNS`: ``f_Hz``, ``fx_amp_N``, ``fy_amp_N``).

    Returns
    -------
    dict
        The CLI's ``summary.json``: ``speed_kmh``, ``dof``, ``fy_peak_hz``, ``fx_peak_hz``
        [Hz] (interpolated between the spectrum's bins), ``peak_resolution_hz`` (the record's
        bin spacing) [Hz], ``fy_rms``, ``fx_rms``, ``fy_band_rms_n``, ``fx_band_rms_n`` (rms of
        the dominant lines) [N], ``preload_deflection_m``, ``fy_mean_before_n``,
        ``fx_mean_before_n``, ``load_n``, ``rayleigh`` (α [1/s], β [s]), ``steps``,
        ``refactors``, ``stats``, ``loaded_vertical_mode_hz``, ``loaded_longitudinal_mode_hz``,
        ``fx_line_mode``, ``fy_line_mode``, ``wall_time_s``, ``wall_per_simulated_s``,
        ``cpu_per_simulated_s``; with ``config["cleat_phases"]`` > 1 also ``phases`` (mean and
        sample standard deviation of ``fy_band_rms_n`` and ``fx_band_rms_n`` over runs with
        the cleat arriving ``j/cleat_phases`` of an impact step later, and the values of each
        run: single runs scatter by about 2 % with that phase).

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message), or ``tire`` given with
        ``config["tire"]``.
    flowmbd.NumericalError
        The rolling simulation failed; ``err.partial`` holds ``speed_kmh``, ``steps_done``,
        ``t_last_s`` and the force history up to the failure (``"forces"``).
    """
    if tire is not None:
        if not isinstance(tire, ReducedTire):
            raise ValueError(f"tire: expected a flowmbd.tire.ReducedTire, got {type(tire).__name__}")
        if isinstance(config, Mapping) and "tire" in config:
            raise ValueError("tire: given both as tire= and as config[\"tire\"]; pass one of them")
    text, forces, spectra = _native.tire_cleat(
        config_json(config), _args.optional_number("speed_kmh", speed_kmh), tire
    )
    out = from_json(text)
    if series:
        out["forces"] = {n: np.asarray(c, dtype=float) for n, c in zip(FORCE_COLUMNS, forces)}
        out["spectra"] = {n: np.asarray(c, dtype=float)
                          for n, c in zip(SPECTRUM_COLUMNS, spectra)}
    return out


def steady(config: Optional[Mapping[str, Any]] = None, tire: Optional["ReducedTire"] = None) -> Result:
    """The steady-state characteristics on a flat (or height-grid) road (``flowmbd-tire
    steady``): each point starts from free rolling, gets its slip angle, drive torque or camber
    angle, rolls ``config["point_time"]`` and is averaged over the last
    ``config["average_time"]``.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire steady --print-config`` (``tire``, ``rig``,
        ``slip_angles_deg`` [deg], ``drive_torques_n_m`` [N m], ``camber_angles_deg`` [deg],
        ``slip_ratios`` [-] (points
        whose spin is prescribed at ``(1 + kappa)`` times the free-rolling spin),
        ``point_time`` [s], ``average_time`` [s]). ``python/examples/tire_steady_curves.py``
        runs it on the small tire and plots F_x(kappa), F_y(alpha), M_z(alpha).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent).

    Returns
    -------
    dict
        The CLI's ``summary.json``: side force ``fy_n`` and aligning moment over
        ``slip_angle_deg``, the cornering stiffness [N/rad], pneumatic trail, longitudinal
        force over drive torque with its slip, in the ISO 8855 wheel frame; over the
        prescribed slips ``prescribed_kappa``, ``prescribed_fx_n`` and the torque holding the
        spin ``prescribed_spin_torque_n_m``; the camber thrust ``fy_camber_n``,
        ``mx_camber_n_m``, ``mz_camber_n_m`` over ``camber_deg`` (ISO 8855 sign, W-axis
        orientation: z along the road normal) and ``camber_stiffness_n_per_rad``; and
        ``magic_formula``: the Magic Formula fit of the points (``fit`` coefficients and
        errors, fitted values, ``warnings``; ``tir`` is ``None``: no file is written), or
        ``None`` with the reason in ``magic_formula_note``; and ``tir_text``: the MF 6.1
        ``.tir`` property file of that fit as text (what the CLI writes as ``tire.tir``), or
        ``None`` without a fit.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        A rolling simulation failed.
    """
    _check_tire(config, tire)
    text, tir = _native.tire_steady(config_json(config), tire)
    out = from_json(text)
    out["tir_text"] = tir
    return out


def _check_tire(config: Optional[Mapping[str, Any]], tire: Optional["ReducedTire"]) -> None:
    """``tire`` must be a :class:`ReducedTire`, and not given twice (``config["tire"]``)."""
    if tire is not None:
        if not isinstance(tire, ReducedTire):
            raise ValueError(f"tire: expected a flowmbd.tire.ReducedTire, got {type(tire).__name__}")
        if isinstance(config, Mapping) and "tire" in config:
            raise ValueError("tire: given both as tire= and as config[\"tire\"]; pass one of them")


#: ``speeds_kmh`` not a parameter of the study (:func:`_tire_series`).
_NO_SPEEDS = object()


def _tire_series(native, config, tire, series: bool, speeds_kmh: Any = _NO_SPEEDS) -> Result:
    """The result of the native tire study ``native`` on ``config`` with the prebuilt ``tire``
    (checked by :func:`_check_tire` first) and, for the studies that take them, the
    ``speeds_kmh`` [km/h]; with its series when ``series``."""
    _check_tire(config, tire)
    speeds = ()
    if speeds_kmh is not _NO_SPEEDS:
        speeds = (_args.optional_numbers("speeds_kmh", speeds_kmh),)
    text, data = native(config_json(config), *speeds, tire)
    return with_series(text, data, series)


def rotating_modes(
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    speeds_kmh: Optional[Sequence[float]] = None,
    series: bool = False,
) -> Result:
    """Complex modes of the rolling tire in the ground-fixed frame at several speeds
    (``flowmbd-tire rotating-modes``): the gyroscopic and convective terms of the flowing
    material (Ribaric (7.17)) split each circumferential order ``n`` into a forward and a
    backward travelling wave (Campbell diagram). Free tire (rim fixed) and loaded tire (the
    rolling preload's patch held).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire rotating-modes --print-config`` (``tire``,
        ``speeds_kmh`` [km/h], ``max_hz`` [Hz], ``ground``, ``load`` [N], ``damped``,
        ``damping``).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent).
    speeds_kmh : speeds [km/h] (replaces ``config["speeds_kmh"]``; the CLI's ``--speeds``).
    series : also return ``"rotating_modes"``: the columns of ``rotating_modes.csv`` (one row
        per mode: ``speed_km_per_h``, ``loaded_flag`` (0 free, 1 loaded), ``f_Hz``, ``n``,
        ``direction_code`` (+1 forward, -1 backward, 0 standing), ``damping_ratio``,
        ``growth_rate_1_per_s``, ``natural_Hz``, ``travelling_share``, ``lateral_share``) as
        numpy arrays.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``speeds`` (per speed ``speed_kmh``, ``spin_rad_s``
        [rad/s], ``free`` and ``loaded`` modes with ``hz`` [Hz], ``n``, ``direction``,
        ``damping_ratio``, ``growth_rate`` [1/s], ``natural_hz`` [Hz], ``travelling``,
        ``lateral_share``, and ``loaded_held_nodes``), ``splits`` (forward/backward frequency
        per speed of the free tire's orders 1–8 per plane, [Hz]; NaN where not found),
        ``zero_speed_max_rel_diff_vs_modes``, ``rayleigh`` (α [1/s], β [s]) and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        An eigen solve or the preload failed.
    """
    return _tire_series(_native.tire_rotating_modes, config, tire, series, speeds_kmh)


def sweep(
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    speeds_kmh: Optional[Sequence[float]] = None,
    series: bool = False,
) -> Result:
    """The cleat test of Ribaric §8.3 at every speed (``flowmbd-tire sweep``; Figs. 8-7, 8-8
    on the drum, 8-14 on the flat road): the peak spectral amplitudes of the spindle forces
    against speed, their local minima (the speed dips) and the spectra as a speed × frequency
    table. For one speed with its force history use :func:`cleat`.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire sweep --print-config`` (``tire``, ``rig``,
        ``speeds_kmh`` [km/h]; ``rig.speed_kmh`` is replaced by each speed).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent).
    speeds_kmh : speeds [km/h] (replaces ``config["speeds_kmh"]``).
    series : also return the CLI's CSV files as numpy arrays: ``"waterfall"`` (the columns of
        ``waterfall.csv``: ``speed_km_per_h``, ``f_Hz``, ``fx_amp_N``, ``fy_amp_N``, every
        run's own bins up to 300 Hz), ``"spectrum_map"`` (``speed_km_per_h``, ``f_Hz`` and the
        amplitude matrices ``fx_amp_N``, ``fy_amp_N`` [N], speeds × frequencies, of
        ``fx_matrix.csv`` and ``fy_matrix.csv``) and ``"run_series"`` (per speed ``"forces"``
        and ``"spectra"``: the columns of ``v<speed>_forces.csv`` and ``v<speed>_spectra.csv``,
        :data:`FORCE_COLUMNS`, :data:`SPECTRUM_COLUMNS`).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``runs`` (per speed the cleat summary without the mode
        labels, see :func:`cleat`), ``fy_peak_amplitude_n``, ``fx_peak_amplitude_n`` [N],
        ``fy_peak_hz`` [Hz] (interpolated), ``peak_resolution_hz`` [Hz],
        ``fy_amplitude_non_monotonic``, ``fy_amplitude_dips_kmh`` [km/h] and ``meaning``.
        ``to_dataframe()`` gives one row per speed of ``runs``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        A run failed (the message names its speed); ``err.partial`` is the list of the
        summaries of the speeds done before it.
    """
    return _tire_series(_native.tire_sweep, config, tire, series, speeds_kmh)


def dips(
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    series: bool = False,
) -> Result:
    """The speed dips of the cleat test (``flowmbd-tire dips``; Ribaric §8.3/§8.5: 40–50 km/h
    on the drum, 45–55 km/h on the road): per ground the cleat's quasi-static enveloping
    profile, the loaded vertical mode, the predicted ring-down amplitude of that mode against
    speed and the measured amplitude of the vertical line in a cleat sweep.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire dips --print-config`` (``tire``, ``rig``,
        ``dips`` (``profile_step`` [m], ``pulse``, ``blocked_below_hz`` [Hz],
        ``predict_speeds_kmh``, ``sweep_speeds_kmh`` [km/h], …), ``grounds``
        (``["drum", "road"]``)). ``{"dips": {"sweep_speeds_kmh": []}}`` predicts only (the
        CLI's ``--no-sweep``).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent).
    series : also return the CLI's CSV files per ground as dicts of numpy arrays:
        ``"profile_<ground>"`` (``cleat_x_m`` [m], ``dfy_N``, ``fx_N`` [N],
        ``active_nodes_count``), ``"prediction_<ground>"`` (``speed_km_per_h``,
        ``amplitude_N``) and, with sweep speeds, ``"sweep_<ground>"`` (``speed_km_per_h``,
        ``line_amplitude_N``).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``grounds`` (per ground ``ground``, ``deflection_m``,
        ``envelope_length_m``, ``geometric_envelope_length_m``, ``contact_node_span_m`` [m],
        ``profile_peak_n`` [N], ``vertical_mode_hz`` [Hz], ``zeta``, ``predicted_dips_kmh``,
        ``measured_dips_kmh``, ``sweep_speeds_kmh`` [km/h], ``line_amplitude_n`` [N]) and
        ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message, e.g. ``dips.profile_step: …``).
    flowmbd.NumericalError
        The profile, the preload or a sweep run failed (the message names the ground).
    """
    return _tire_series(_native.tire_dips, config, tire, series)


def pressure(
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    series: bool = False,
) -> Result:
    """The preloaded contact patch on the drum and on a flat road (``flowmbd-tire pressure``;
    Ribaric Fig. 8-12): static contact with Lagrange multipliers (§7.3) under the vertical
    load, the contact-node forces and the patch extent.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire pressure --print-config`` (``tire``,
        ``load`` [N], ``drum_radius`` [m]).
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]`` (which must then be absent).
    series : also return ``"patch_drum"`` and ``"patch_road"``: the columns of
        ``patch_<ground>.csv`` (``x_m``, ``y_m``, ``z_m``: undeformed contact-node position
        [m]; ``force_N``: its normal force [N], 0 off the patch) as numpy arrays.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``drum`` and ``road``, each with ``deflection_m`` [m],
        ``nodes_in_contact``, ``peak_node_force_n`` [N] and ``length_m`` [m]; and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The contact solve failed.
    """
    return _tire_series(_native.tire_pressure, config, tire, series)


def modes(config: Optional[Mapping[str, Any]] = None, series: bool = False) -> Result:
    """Eigenfrequencies of the tire with the rim fixed, full FE model against the reduced
    model (the validation of the reduction, Ribaric §8.2), and the modes of the loaded tire
    (preloaded patch held, wheel fixed) with their effective spindle masses
    (``flowmbd-tire modes``). The full FE model is part of the study, so the tire is built
    from ``config["tire"]`` and reduced here (no ``tire=``).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire modes --print-config`` (``tire``,
        ``count``, ``ground``, ``load`` [N]).
    series : also return ``"modes"`` (``mode``, ``full_Hz``, ``reduced_Hz``) and
        ``"loaded_modes"`` (``mode``, ``f_Hz``, ``spindle_fx_N_per_sqrt_kg``,
        ``spindle_fy_N_per_sqrt_kg``, ``spindle_lateral_N_per_sqrt_kg``,
        ``vertical_mass_kg``, ``longitudinal_mass_kg``): the columns of ``modes.csv`` and
        ``loaded_modes.csv`` as numpy arrays.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``full_hz``, ``reduced_hz`` [Hz],
        ``max_rel_error_below_240hz``, ``loaded_held_nodes``, ``loaded_hz`` [Hz],
        ``loaded_vertical_mode_hz`` [Hz], ``loaded_vertical_mass_kg`` [kg],
        ``loaded_longitudinal_mode_hz`` [Hz] and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        An eigen solve or the preload failed.
    """
    text, data = _native.tire_modes(config_json(config))
    return with_series(text, data, series)


class Simulation(Stepping):
    """The reduced tire rolling on the cleat rig, stepped in time: started as the cleat test
    starts it (the rolling preload; the cleat reaches the patch centre at ``settle_time``) and
    advanced by the cleat test's own step (sub-stepped through the impact; Rust:
    ``tire::start_rolling`` and ``tire::rig_step``), so that stepping it reproduces
    :func:`cleat` step by step. Read the spindle forces of any state, change the drive torque
    or prescribe the spin rate (:meth:`prescribe_spin`, its :attr:`reaction_torque`) between
    steps, observe it.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire cleat --print-config`` (``tire``, ``rig``:
        ``speed_kmh`` [km/h], ``load`` [N], ``settle_time`` and ``record_time`` [s],
        ``ground``, ``rolling``, ``wheel``, ...); missing keys keep their defaults.
    tire : a :class:`ReducedTire` from :func:`reduce`, used instead of reducing
        ``config["tire"]``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The preload failed.

    Example
    -------
    >>> sim = flowmbd.tire.Simulation(config, tire=tire)
    >>> sim.run_to(sim.settle_time + 0.05, observer=lambda s: print(s.forces()["fy_N"]))
    """

    def __init__(
        self, config: Optional[Mapping[str, Any]] = None, tire: Optional["ReducedTire"] = None
    ) -> None:
        if tire is not None and not isinstance(tire, ReducedTire):
            raise ValueError(f"tire: expected a flowmbd.tire.ReducedTire, got {type(tire).__name__}")
        self._sim = _native.TireSimulation(config_json(config), tire)

    t = Native("Time [s] (the cleat hit at ``settle_time``).")
    settle_time = Native("The rig's ``settle_time`` [s]: when the cleat reaches the patch centre.")
    step_size = Native("The rig's step ``rolling.time_step`` [s].")
    spin = Native("Spin rate [rad/s].")
    coordinates = Native("The reduced coordinates ``z`` of the tire (numpy copy).")
    normal_forces = Native("Normal force per contact node [N] (numpy copy).")
    contact_positions = Native("Contact-node positions in the wheel frame [m] (n x 3).")

    @property
    def drive_torque(self) -> float:
        """Drive torque about the wheel axis [N m] (0: free rolling); settable between steps."""
        return self._sim.drive_torque

    @drive_torque.setter
    def drive_torque(self, torque: float) -> None:
        self._sim.drive_torque = _args.number("drive_torque", torque)

    reaction_torque = Native(
        "Reaction torque of the prescribed spin about the spin axis +y in the last step [N m] "
        "(0 when the spin is free; Rust: ``RollingTire::reaction_torque``)."
    )
    spin_torque = Native(
        "Total torque on the wheel about +y in the last step [N m]: :attr:`drive_torque` plus "
        ":attr:`reaction_torque`."
    )

    @property
    def prescribed_spin(self) -> Optional[float]:
        """The prescribed spin rate [rad/s], ``None`` while the spin is free
        (:meth:`prescribe_spin`)."""
        return self._sim.prescribed_spin

    def prescribe_spin(self, rate: Optional[float]) -> None:
        """Prescribe the wheel's spin rate for the following steps, or free it again.

        The spin becomes a kinematic constraint on the spin coordinate of the stepper (Rust:
        ``RollingTire::prescribe_spin``): over the next step the rate goes linearly from its
        present value to ``rate``, then stays there; the torque that holds it is
        :attr:`reaction_torque` (a :attr:`drive_torque` acts on top of it). The longitudinal
        slip is ``kappa = rate / spin_free - 1`` with the free-rolling spin ``spin_free``.

        Parameters
        ----------
        rate : spin rate [rad/s] (positive: rolling forwards), or ``None`` to free the spin
            (driven by :attr:`drive_torque` again).

        Raises
        ------
        ValueError
            ``rate`` is not a finite number (the message names ``rate``).
        """
        self._sim.prescribe_spin(None if rate is None else _args.number("rate", rate))

    def forces(self) -> dict:
        """The cleat test's force row of the present state: the columns of its ``forces``
        series (``t_s`` [s] from the hit, ``fx_N``, ``fy_N`` (vertical), ``f_lateral_N`` [N],
        ``spin_rad_per_s``, ``active_nodes_count``, ``normal_sum_N`` [N], ``mx_N_m``,
        ``my_N_m``, ``mz_N_m`` [N m])."""
        return self._sim.forces()

    def state(self) -> dict:
        """The state (copies), to continue from with :meth:`set_state`: ``t`` [s]; the
        simulation's reduced coordinates ``z``, their rates ``zd`` and accelerations ``zdd``
        and the generalized-alpha pseudo-accelerations ``acc`` (arrays; the modal, possibly
        mirror-half, coordinates the simulation steps: :attr:`coordinates` gives the tire's);
        the spin angle ``theta`` [rad], ``theta_d`` [rad/s], ``theta_dd`` and ``theta_acc``
        [rad/s^2]; the normal force per contact node ``lambda`` [N], the friction force per
        node ``friction`` (n x 3) [N] and the net contact force ``contact_force`` (3) [N]."""
        return self._sim.state()

    def set_state(self, state: Mapping[str, Any]) -> None:
        """Continue from ``state``, a dict of :meth:`state` saved earlier from this simulation
        or one of the same tire and configuration. The following steps depend on the state
        only: restarted here or in a fresh simulation they are the same; against the run
        that was never stopped they differ by what re-forming the spin-frozen matrices
        changes (on the test tire 5e-4 of the load before a cleat; Rust:
        ``RollingTire::set_state``). Raises ``ValueError`` naming the key (``state.z``) of a
        missing key, a wrong length or a value that is not finite."""
        import numpy as np

        if not isinstance(state, Mapping):
            raise ValueError(f"state: expected a dict from state(), got {type(state).__name__}")
        arrays = ("z", "zd", "zdd", "acc", "lambda", "contact_force")
        converted = {}
        for k, v in state.items():
            if k != "friction" and k not in arrays:
                converted[k] = _args.number(f"state.{k}", v)
                continue
            try:
                a = np.ascontiguousarray(v, dtype=float)
                converted[k] = a.reshape(-1, 3) if k == "friction" else a.ravel()
            except (TypeError, ValueError) as e:
                raise ValueError(f"state.{k}: expected an array of numbers ({e})") from None
        self._sim.set_state(converted)


def _motion_json(motion: Mapping[str, Any]) -> str:
    """The JSON of a wheel-centre motion dict (``height`` [m], ``velocity`` [m/s] (3, road
    frame), ``yaw``, ``camber`` [rad], ``spin_rate`` [rad/s]), checked for its keys."""
    import json

    if not isinstance(motion, Mapping):
        raise ValueError(f"motion: expected a dict, got {type(motion).__name__}")
    out = {}
    for k, v in motion.items():
        if k == "velocity":
            vel = [_args.number(f"motion.velocity[{i}]", x) for i, x in enumerate(v)]
            if len(vel) != 3:
                raise ValueError(f"motion.velocity: {len(vel)} values, must be 3 (x, y, z)")
            out[k] = vel
        else:
            out[k] = _args.number(f"motion.{k}", v)
    return json.dumps(out)


class CoSimulation:
    """The reduced tire on a flat road driven by a prescribed wheel-centre motion (issue 38
    items 1, 2 and 4; Rust: ``tire::motion::CoSimulation``, the same implementation as the
    tire FMU of :func:`build_fmu`): each :meth:`do_step` holds the motion over a communication
    step and returns the six loads of the tire on the wheel in the ISO 8855 wheel frame.

    The motion is a dict: ``height`` of the wheel centre above the road [m], its ``velocity``
    over the road (road frame x forward, y left, z up) [m/s], the wheel's ``yaw`` about z and
    ``camber`` about its x axis [rad] (ISO 8855, within ±30°; loads then in the W-axis
    orientation) and its prescribed
    ``spin_rate`` [rad/s]. The spindle's acceleration (the difference of the velocities over
    a step) loads the tire with its inertia ``-M a``.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-tire cleat --print-config`` (its ``rig``: load,
        damping, ``rolling`` with ``friction`` and ``time_step``, the largest internal step).
    tire : a :class:`ReducedTire` used instead of reducing ``config["tire"]``.
    motion : the start motion; default the rig's steady start (:attr:`motion` afterwards).

    Raises
    ------
    ValueError
        Bad input: a key of ``config`` or ``motion`` (named in the message, ``motion.camber``
        for a camber other than 0).
    flowmbd.NumericalError
        The preload of the start failed.

    Example
    -------
    >>> cs = flowmbd.tire.CoSimulation(config, tire=tire)
    >>> m = dict(cs.motion, height=cs.motion["height"] - 0.001)  # lower the wheel by 1 mm
    >>> cs.do_step(0.01, m)["fz"]
    """

    def __init__(
        self,
        config: Optional[Mapping[str, Any]] = None,
        tire: Optional["ReducedTire"] = None,
        motion: Optional[Mapping[str, Any]] = None,
    ) -> None:
        if tire is not None and not isinstance(tire, ReducedTire):
            raise ValueError(f"tire: expected a flowmbd.tire.ReducedTire, got {type(tire).__name__}")
        m = None if motion is None else _motion_json(motion)
        self._sim = _native.TireCoSimulation(config_json(config), tire, m)

    @property
    def t(self) -> float:
        """Time [s]."""
        return self._sim.t

    @property
    def motion(self) -> dict:
        """The motion of the last communication point."""
        return self._sim.motion()

    def do_step(self, h: float, motion: Mapping[str, Any]) -> dict:
        """One communication step of ``h`` [s] with ``motion`` held (internal steps of at
        most ``rig.rolling.time_step``, the last ending on ``t + h``).

        Parameters
        ----------
        h : communication step [s] (> 0).
        motion : the wheel-centre motion held over the step (the keys of :attr:`motion`).

        Returns
        -------
        dict
            ``fx``, ``fy``, ``fz`` [N], ``mx``, ``my``, ``mz`` [N m] (the loads of the tire on
            the wheel in the ISO 8855 wheel frame at the wheel centre; ``fz`` the carried load)
            and ``spin_torque`` [N m] (the torque that holds the prescribed spin).

        Raises
        ------
        ValueError
            Bad input (``communication_step`` or ``motion.<key>`` named).
        flowmbd.NumericalError
            An internal step failed (the state is that of the last step taken).
        """
        return self._sim.do_step(_args.number("h", h), _motion_json(motion))


def fmu_library() -> str:
    """The compiled FMU library to pack into an FMU.

    The library ``libflowmbd_tire_fmu.so`` is built by ``cargo build --release -p
    flowmbd-tire-fmu``; it is looked up as ``$FLOWMBD_FMU_LIB``, else in ``$FLOWMBD_BIN_DIR``,
    else in ``target/release`` under the working folder (the workspace root).

    Returns
    -------
    str
        Its path.

    Raises
    ------
    FileNotFoundError
        Not found: the message says how to build it.
    """
    import os
    import pathlib
    import sys

    if os.environ.get("FLOWMBD_FMU_LIB"):
        return os.environ["FLOWMBD_FMU_LIB"]
    name = {"darwin": "libflowmbd_tire_fmu.dylib", "win32": "flowmbd_tire_fmu.dll"}.get(
        sys.platform, "libflowmbd_tire_fmu.so"
    )
    dirs = []
    if os.environ.get("FLOWMBD_BIN_DIR"):
        dirs.append(pathlib.Path(os.environ["FLOWMBD_BIN_DIR"]))
    dirs.append(pathlib.Path.cwd() / "target" / "release")
    for d in dirs:
        if (d / name).exists():
            return str(d / name)
    raise FileNotFoundError(
        f"{name} not found in {[str(d) for d in dirs]}: build it with "
        "`cargo build --release -p flowmbd-tire-fmu` or set FLOWMBD_FMU_LIB"
    )


def build_fmu(
    out: str,
    config: Optional[Mapping[str, Any]] = None,
    tire: Optional["ReducedTire"] = None,
    library: Optional[str] = None,
) -> dict:
    """Write the FMI 3.0 co-simulation FMU of the tire to ``out`` (a ``.fmu`` zip:
    ``modelDescription.xml``, ``binaries/<platform>/flowmbd_tire_fmu.so`` = ``library``
    (default :func:`fmu_library`), ``resources/`` with the reduced tire and the rig of
    ``config``). Inputs: wheel-centre position ``x``, ``y``, ``z`` [m], velocity ``vx``,
    ``vy``, ``vz`` [m/s] (road frame), ``yaw``, ``camber`` [rad], ``spin_rate`` [rad/s];
    outputs ``Fx`` ... ``Mz`` (ISO 8855 wheel frame) and ``spin_torque``; parameters
    ``load`` [N], ``friction``, ``time_step`` [s] (see :class:`CoSimulation`). The CLI's
    ``flowmbd-tire fmu`` writes the same FMU with a summary of its variables.

    Parameters
    ----------
    out : path of the ``.fmu`` to write (written through a temporary file).
    config : dict with the keys of ``flowmbd-tire cleat --print-config`` (``tire``, ``rig``).
    tire : a :class:`ReducedTire` used instead of reducing ``config["tire"]``.
    library : the compiled FMU library to pack (default :func:`fmu_library`).

    Returns
    -------
    dict
        The start motion (the inputs' start values, the rig's steady start): ``height`` [m],
        ``velocity`` [m/s], ``yaw``, ``camber`` [rad], ``spin_rate`` [rad/s].

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    OSError
        The library cannot be read or the FMU cannot be written.
    flowmbd.NumericalError
        The preload of the start failed.
    """
    if tire is not None and not isinstance(tire, ReducedTire):
        raise ValueError(f"tire: expected a flowmbd.tire.ReducedTire, got {type(tire).__name__}")
    lib = library if library is not None else fmu_library()
    return _native.tire_build_fmu(str(out), str(lib), config_json(config), tire)
