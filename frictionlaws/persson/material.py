"""A viscoelastic rubber described by a generalised Maxwell (Prony) series.

The complex modulus at angular frequency omega [rad/s] and the reference
temperature is

    E(omega) = E_inf + sum_i E_i (i omega tau_i) / (1 + i omega tau_i),

so ``E' = E_inf + sum E_i w^2 tau_i^2/(1 + w^2 tau_i^2)`` and
``E'' = sum E_i w tau_i/(1 + w^2 tau_i^2)``, with non-negative ``E_inf`` and
``E_i`` (a thermodynamically admissible, causal material).  At temperature T
the modulus is that of the reduced frequency ``a_T(T) omega`` (time-temperature
superposition); ``log10 a_T`` is either a WLF equation or a table of measured
shifts interpolated linearly in T.

The Prony terms are fitted by non-negative least squares (``scipy.optimize.nnls``)
on relaxation times spaced evenly in log10 tau, storage and loss modulus
weighted by the measured ``|E*|`` (relative residuals), as in
Park and Schapery, Int. J. Solids Struct. 36 (1999) 1653-1675 (collocation on a
fixed grid of relaxation times).
"""

from __future__ import annotations

import functools
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..law import NUMPY
from ..viscoelastic.temperature import wlf_formula

__all__ = ["Shift", "Material", "fit_prony", "material_from_master_curve", "material_from_csv",
           "default_material", "havriliak_negami", "tread_compound"]


@dataclass(frozen=True, eq=False)
class Shift:
    """log10 a_T(T): a WLF equation, or a table of shifts interpolated in T.

    Attributes
    ----------
    T_ref : float
        Reference temperature [K] (log10 a_T = 0).
    C1, C2 : float, optional
        WLF constants (C2 in K), used when no table is given.
    T, log_aT : numpy.ndarray, optional
        A table of shifts [K] and [decades]: interpolated linearly, continued
        with the slope of the end intervals outside it.
    """

    T_ref: float
    C1: float | None = None
    C2: float | None = None
    T: np.ndarray | None = None
    log_aT: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.T is None and (self.C1 is None or self.C2 is None):
            raise InputError("a shift needs WLF constants C1, C2 or a table of T and log_aT")
        if self.T is not None:
            T = np.asarray(self.T, dtype=float)
            la = np.asarray(self.log_aT, dtype=float)
            if T.size < 2 or T.shape != la.shape or np.any(np.diff(T) <= 0):
                raise InputError("a shift table needs two or more increasing temperatures, "
                                 "one log_aT each")

    def __call__(self, T: Any) -> np.ndarray:
        """log10 a_T at ``T`` [K]."""
        T = np.asarray(T, dtype=float)
        if self.T is None:
            assert self.C1 is not None and self.C2 is not None
            if np.any(T <= self.T_ref - self.C2):
                raise InputError(f"T below the WLF pole T_ref - C2 = "
                                 f"{self.T_ref - self.C2:.2f} K")
            return np.asarray(wlf_formula(NUMPY, T, self.C1, self.C2, self.T_ref))
        assert self.log_aT is not None
        tt, la = np.asarray(self.T), np.asarray(self.log_aT)
        out = np.interp(T, tt, la)
        lo_slope = (la[1] - la[0]) / (tt[1] - tt[0])
        hi_slope = (la[-1] - la[-2]) / (tt[-1] - tt[-2])
        out = np.where(T < tt[0], la[0] + lo_slope * (T - tt[0]), out)
        return np.where(T > tt[-1], la[-1] + hi_slope * (T - tt[-1]), out)

    def describe(self) -> str:
        """One line saying what the shift is."""
        if self.T is None:
            return (f"WLF: C1 = {self.C1:.4g}, C2 = {self.C2:.4g} K, "
                    f"T_ref = {self.T_ref:.2f} K")
        return (f"table of {np.size(self.T)} shifts from {np.min(self.T):.2f} to "
                f"{np.max(self.T):.2f} K, T_ref = {self.T_ref:.2f} K")


@dataclass(frozen=True, eq=False)
class Material:
    """A Prony-series rubber with its temperature shift.

    Attributes
    ----------
    E_inf : float
        Equilibrium (rubbery) modulus [Pa].
    E_i : numpy.ndarray
        Prony moduli [Pa], non-negative.
    tau : numpy.ndarray
        Relaxation times [s] at the reference temperature.
    shift : Shift
        log10 a_T(T).
    nu : float
        Poisson ratio (0.5 for rubber).
    rms_rel : float
        rms relative misfit of the fit (storage and loss together), NaN when
        the terms were given.
    source : str
        Where the material comes from.
    T_range : tuple of float, optional
        Temperatures [K] the material's data cover (its DMA sweeps, or the
        range its WLF constants were stated for): the theory refuses other
        temperatures.  Default: the shift table's range; for a WLF shift
        without a stated range, the WLF equation's own range from the pole
        ``T_ref - C2`` (excluded) to ``T_ref + 100 K``.
    omega_range : tuple of float, optional
        Reduced angular frequencies [rad/s] at ``T_ref`` the measured modulus
        covers (None: a modulus given as a function, valid at every
        frequency).  The theory warns where a sliding condition excites only
        frequencies outside it.
    """

    E_inf: float
    E_i: np.ndarray
    tau: np.ndarray
    shift: Shift
    nu: float = 0.5
    rms_rel: float = math.nan
    source: str = ""
    T_range: tuple[float, float] | None = None
    omega_range: tuple[float, float] | None = None
    _cache: dict[str, Any] = field(default_factory=dict, repr=False)

    def temperature_range(self) -> tuple[float, float]:
        """The temperatures [K] the material's data cover (see :attr:`T_range`)."""
        if self.T_range is not None:
            try:
                lo, hi = (float(x) for x in self.T_range)
            except (TypeError, ValueError):
                raise InputError(f"T_range {self.T_range!r} must be two temperatures [K]"
                                 ) from None
            if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
                raise InputError(f"T_range ({lo:g}, {hi:g}) K must be finite, above 0 K and "
                                 "increasing")
            return lo, hi
        sh = self.shift
        if sh.T is not None:
            return (float(np.min(sh.T)), float(np.max(sh.T)))
        assert sh.C2 is not None
        return (float(np.nextafter(sh.T_ref - sh.C2, math.inf)), float(sh.T_ref + 100.0))

    def modulus(self, omega: Any, T: Any = None) -> np.ndarray:
        """Complex modulus E(omega, T) [Pa] at angular frequency ``omega`` [rad/s]."""
        w = np.asarray(omega, dtype=float)
        if T is not None:
            w = w * 10.0 ** self.shift(T)
        x = w[..., None] * self.tau
        return self.E_inf + np.sum(self.E_i * (1j * x) / (1.0 + 1j * x), axis=-1)

    @property
    def E_glassy(self) -> float:
        """High-frequency (glassy) modulus E_inf + sum E_i [Pa]."""
        return float(self.E_inf + np.sum(self.E_i))

    def summary(self) -> dict[str, Any]:
        """JSON-able description with units."""
        return {"E_inf": self.E_inf, "E_inf_unit": "Pa", "E_i": self.E_i.tolist(),
                "E_i_unit": "Pa", "tau": self.tau.tolist(), "tau_unit": "s",
                "terms": int(self.E_i.size), "nu": self.nu, "rms_rel": self.rms_rel,
                "shift": self.shift.describe(), "source": self.source,
                "T_range": list(self.temperature_range()), "T_range_unit": "K"}


def fit_prony(omega: Any, E_stor: Any, E_loss: Any, *, per_decade: float = 1.0,
              extend: float = 1.0) -> tuple[float, np.ndarray, np.ndarray, float]:
    """Non-negative Prony terms fitted to storage and loss modulus.

    Parameters
    ----------
    omega : array-like
        Angular frequency [rad/s] (reduced to the reference temperature).
    E_stor, E_loss : array-like
        Storage and loss modulus [Pa], positive.
    per_decade : float
        Relaxation times per decade of frequency.
    extend : float
        Decades the tau grid reaches beyond the data at each end.

    Returns
    -------
    E_inf, E_i, tau, rms_rel
        Moduli [Pa], relaxation times [s] and the rms relative misfit.
        Terms fitted to zero are dropped.
    """
    w = np.asarray(omega, dtype=float).ravel()
    s = np.asarray(E_stor, dtype=float).ravel()
    loss = np.asarray(E_loss, dtype=float).ravel()
    if not (w.size == s.size == loss.size) or w.size < 3:
        raise InputError("Prony fit: omega, E_stor and E_loss need the same length (>= 3)")
    for name, arr in (("omega", w), ("E_stor", s), ("E_loss", loss)):
        bad = np.flatnonzero(~np.isfinite(arr) | (arr <= 0))
        if bad.size:
            raise InputError(f"Prony fit: {name} must be positive and finite; not at points "
                             f"{bad[:5].tolist()}")
    from scipy.optimize import nnls

    lo, hi = np.log10(w.min()) - extend, np.log10(w.max()) + extend
    n = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
    tau = 1.0 / 10.0 ** np.linspace(lo, hi, n)
    x = w[:, None] * tau[None, :]
    a_s = np.column_stack([np.ones_like(w), x**2 / (1 + x**2)])
    a_l = np.column_stack([np.zeros_like(w), x / (1 + x**2)])
    scale = np.hypot(s, loss)
    a = np.vstack([a_s / scale[:, None], a_l / scale[:, None]])
    b = np.concatenate([s / scale, loss / scale])
    col = np.max(np.abs(a), axis=0)
    col[col == 0] = 1.0
    coef, _ = nnls(a / col, b, maxiter=50 * a.shape[1])
    coef = coef / col
    rms = float(np.sqrt(np.mean((a @ coef - b) ** 2)))
    keep = coef[1:] > 0
    return float(coef[0]), coef[1:][keep], tau[keep], rms


def material_from_master_curve(mc: Any, *, nu: float = 0.5, per_decade: float = 1.0,
                               wlf: bool = False, source: str = "") -> Material:
    """A material from a :class:`frictionlaws.viscoelastic.mastercurve.MasterCurve` of E', E''.

    The master curve's ``x`` is a frequency [Hz] and its properties are
    ``E_stor`` and ``E_loss`` [Pa].  The shift is the master curve's own table
    of shifts, or its fitted WLF equation when ``wlf`` is True.
    """
    pts = mc.points()
    names = list(mc.y_names)
    if "E_stor" not in names or "E_loss" not in names:
        raise InputError(f"the master curve must carry E_stor and E_loss (has {names})")
    E_inf, E_i, tau, rms = fit_prony(2 * np.pi * pts["x_reduced"], pts["E_stor"],
                                     pts["E_loss"], per_decade=per_decade)
    if wlf:
        if mc.wlf is None:
            raise InputError("the master curve has no WLF fit")
        shift = Shift(mc.T_ref, C1=mc.wlf.C1, C2=mc.wlf.C2)
    else:
        shift = Shift(mc.T_ref, T=mc.temperatures, log_aT=np.asarray(mc.log_aT, dtype=float))
    temps = np.asarray(mc.temperatures, dtype=float)
    w = 2 * np.pi * np.asarray(pts["x_reduced"], dtype=float)
    return Material(E_inf, E_i, tau, shift, nu, rms, source,
                    T_range=(float(temps.min()), float(temps.max())),
                    omega_range=(float(w.min()), float(w.max())))


def _check_nu(nu: float) -> None:
    if not 0.0 <= nu <= 0.5:
        raise InputError(f"Poisson ratio nu = {nu} outside [0, 0.5]")


def material_from_csv(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                      units: Mapping[str, str] | None = None, T_ref: float | None = None,
                      nu: float = 0.5, per_decade: float = 1.0, wlf: bool = False) -> Material:
    """A material from a CSV of DMA sweeps: frequency, E', E'' and temperature.

    Parameters
    ----------
    path : path-like
        CSV with columns ``f [Hz]``, ``E_stor [MPa]``, ``E_loss [MPa]``,
        ``T [degC]`` (units in the headers, any pint unit of the right kind),
        read by :mod:`frictionlaws.io`; several temperatures are shifted into a
        master curve by :func:`frictionlaws.viscoelastic.mastercurve.build_master_curve`, one
        temperature is taken as the master curve itself (then ``T`` may be
        absent and the shift is a WLF with ``T_ref`` and the universal
        constants, C1 = 17.44, C2 = 51.6 K, and the material's data cover
        ``T_ref`` alone: give ``Material.T_range`` to evaluate elsewhere).
    columns : mapping, optional
        ``f``, ``E_stor``, ``E_loss``, ``T`` -> column names in the file.
    units : mapping, optional
        Column name -> unit for headers without one.
    T_ref : float, optional
        Reference temperature [K].
    nu, per_decade, wlf
        As :func:`material_from_master_curve`.
    """
    from ..viscoelastic.mastercurve import build_master_curve
    from ._table import read_columns

    _check_nu(nu)
    cols = {"f": "f", "E_stor": "E_stor", "E_loss": "E_loss", "T": "T"}
    cols.update(columns or {})
    kinds = {"f": "frequency", "E_stor": "p", "E_loss": "p", "T": "T"}
    try:
        d = read_columns(path, {k: (cols[k], kinds[k]) for k in kinds}, units)
    except InputError as exc:
        if exc.column != cols["T"]:
            raise
        d = read_columns(path, {k: (cols[k], kinds[k]) for k in ("f", "E_stor", "E_loss")},
                         units)
        if T_ref is None:
            raise InputError("one-temperature data without a T column: give T_ref",
                             file=str(path)) from None
        E_inf, E_i, tau, rms = fit_prony(2 * np.pi * d["f"], d["E_stor"], d["E_loss"],
                                         per_decade=per_decade)
        w = 2 * np.pi * d["f"]
        return Material(E_inf, E_i, tau, Shift(T_ref, C1=17.44, C2=51.6), nu, rms, str(path),
                        T_range=(T_ref, T_ref), omega_range=(float(w.min()), float(w.max())))
    mc = build_master_curve(d["f"], np.column_stack([d["E_stor"], d["E_loss"]]), d["T"],
                            T_ref=T_ref, y_names=["E_stor", "E_loss"], x_name="f")
    return material_from_master_curve(mc, nu=nu, per_decade=per_decade, wlf=wlf,
                                      source=str(path))


#: Reference temperature of the packaged material [K] (the sweep nearest 20 degC).
DEFAULT_T_REF = 293.15


@functools.lru_cache(maxsize=1)
def default_material() -> Material:
    """The packaged material: the DMA sweeps of ``datasets/dma-pyvisco`` shifted into a
    master curve at the sweep nearest 20 degC, one Prony term per decade, and the
    master curve's own table of shifts (these shifts do not follow WLF; see
    ``datasets/README.md``).  Built on first use and cached.
    """
    from ..viscoelastic.mastercurve import build_master_curve, load_dma_example

    d = load_dma_example()
    mc = build_master_curve(d["f"], np.column_stack([d["E_stor"], d["E_loss"]]), d["T"],
                            groups=d["set"], T_ref=DEFAULT_T_REF, y_names=["E_stor", "E_loss"],
                            x_name="f", fit=False)
    return material_from_master_curve(mc, source="datasets/dma-pyvisco (NREL pyvisco DMA "
                                      "sweeps), master curve by "
                                      "frictionlaws.viscoelastic.mastercurve")


def havriliak_negami(omega: Any, E_r: float, E_g: float, tau0: float, alpha: float,
                     beta: float) -> np.ndarray:
    """Complex modulus of the Havriliak-Negami form [Pa].

    ``E(omega) = E_g + (E_r - E_g) / (1 + (i omega tau0)^alpha)^beta``: the rubbery
    modulus ``E_r`` at low and the glassy ``E_g`` at high angular frequency
    ``omega`` [rad/s] (S. Havriliak, S. Negami, Polymer 8 (1967) 161).
    """
    w = np.asarray(omega, dtype=float)
    return E_g + (E_r - E_g) / (1.0 + (1j * w * tau0) ** alpha) ** beta


#: The packaged tread compound (``datasets/tread-compound/``).
TREAD_FILE = "tread-compound/tread-hn.json"


def _value(spec: Mapping[str, Any], key: str, file: str) -> float:
    try:
        x = float(spec[key]["value"])
    except (KeyError, TypeError, ValueError):
        raise InputError(f"expected a number under '{key}' -> 'value'", file=file) from None
    if not math.isfinite(x):
        raise InputError(f"'{key}' is not finite", file=file)
    return x


@functools.lru_cache(maxsize=1)
def _tread_spec() -> dict[str, Any]:
    from ..io import datasets_dir

    text = (datasets_dir() / TREAD_FILE).read_text(encoding="utf-8")
    spec: dict[str, Any] = json.loads(text)
    return spec


def tread_temperature_range() -> tuple[float, float]:
    """The temperatures [K] the packaged tread compound is declared for (no Prony fit)."""
    lo, hi = (float(x) for x in _tread_spec()["shift"]["T_range"]["value"])
    return lo, hi


@functools.lru_cache(maxsize=1)
def tread_compound() -> Material:
    """The packaged tread compound (``datasets/tread-compound/tread-hn.json``).

    An illustrative passenger-car tread rubber constructed, not measured: a
    Havriliak-Negami master curve (:func:`havriliak_negami`) at its glass
    transition T_g, shifted by the universal WLF constants, with the
    temperature range T_g .. T_g + 100 K; every number and where it comes from
    is in the file and in ``datasets/tread-compound/PROVENANCE.md``.  The Prony series is fitted
    to the form on first use (:func:`fit_prony`) and cached.
    """
    from ..viscoelastic.temperature import WLF_PRESETS

    d = _tread_spec()
    m, sh, pr = d["modulus"], d["shift"], d["prony"]
    E_r, E_g, tau0, alpha, beta = (_value(m, k, TREAD_FILE) for k in
                                   ("E_r", "E_g", "tau0", "alpha", "beta"))
    wlf = WLF_PRESETS[sh["wlf_preset"]]
    T_g = _value(sh, "T_g", TREAD_FILE)
    lo, hi = tread_temperature_range()
    w = np.logspace(math.log10(pr["omega_min"]), math.log10(pr["omega_max"]), int(pr["points"]))
    E = havriliak_negami(w, E_r, E_g, tau0, alpha, beta)
    E_inf, E_i, tau, rms = fit_prony(w, E.real, E.imag, per_decade=float(pr["per_decade"]),
                                     extend=0.0)
    return Material(E_inf, E_i, tau, Shift(wlf.T_ref(T_g), C1=wlf.C1, C2=wlf.C2),
                    _value(d, "nu", TREAD_FILE), rms, f"datasets/{TREAD_FILE}: {d['title']}",
                    T_range=(lo, hi))
