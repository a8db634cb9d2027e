"""Surface roughness power spectra C(q) for Persson's theory.

Conventions (Persson et al., J. Phys.: Condens. Matter 17 (2005) R1):
the isotropic 2-D spectrum ``C(q) = (2 pi)^-2 int d^2x <h(x) h(0)> exp(-i q.x)``
[m^4], so that ``<h^2> = int d^2q C(q) = 2 pi int q C(q) dq``; the 1-D
spectrum of a line scan ``C1(q) = (2 pi)^-1 int dx <h(x) h(0)> exp(-i q x)``
[m^3], two-sided, ``<h^2> = int_{-inf}^{inf} C1(q) dq``.

1-D to 2-D conversion.  For an isotropic surface ``C1(qx) = int dqy C(sqrt(qx^2 + qy^2))``.
For a self-affine spectrum ``C = C0 (q/q0)^(-2(1+H))`` this gives exactly

    C(q) = C1(q) Gamma(H + 1) / (sqrt(pi) Gamma(H + 1/2) q),

(``C = C1/(2q)`` at H = 1/2).  :func:`psd_from_profile` applies it with the local
Hurst exponent ``H(q) = -(1 + d ln C1 / d ln q)/2`` of the measured 1-D
spectrum (clipped to [0, 1]): exact on a self-affine band, an approximation
where the slope changes.
"""

from __future__ import annotations

import math
import os
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError

__all__ = ["SelfAffine", "TabulatedPSD", "psd_from_profile", "psd_from_profile_csv",
           "asphalt_like", "one_d_to_two_d", "check_roughness", "RoughnessWarning",
           "SLOPE_WARN", "SLOPE_MAX"]

#: rms slope of the band q0..q1 above which :func:`check_roughness` warns, and above
#: which it refuses the surface (see there).
SLOPE_WARN, SLOPE_MAX = 3.0, 10.0


class RoughnessWarning(UserWarning):
    """A surface steeper than road surfaces are: the theory's result is doubtful."""


@dataclass(frozen=True)
class SelfAffine:
    """A self-affine (fractal) surface: ``C(q) = C0 (q/q0)^(-2(1+H))`` for q >= q0.

    Attributes
    ----------
    q0 : float
        Long-wavelength roll-off wavenumber [1/m]: C = 0 below it.
    H : float
        Hurst exponent (0 < H < 1; fractal dimension 3 - H).
    C0 : float
        Spectrum at q0 [m^4].
    q1 : float
        Short-wavelength cut-off [1/m] (where the theory's integrals stop).
    """

    q0: float
    H: float
    C0: float
    q1: float = math.inf

    def __post_init__(self) -> None:
        if not (self.q0 > 0 and math.isfinite(self.q0)):
            raise InputError(f"q0 = {self.q0} must be a positive wavenumber [1/m]")
        if not 0.0 < self.H < 1.0:
            raise InputError(f"Hurst exponent H = {self.H} outside (0, 1)")
        if not (self.C0 > 0 and math.isfinite(self.C0)):
            raise InputError(f"C0 = {self.C0} must be positive [m^4]")
        if not self.q1 > self.q0:
            raise InputError(f"q1 = {self.q1} must exceed q0 = {self.q0} [1/m]")

    @classmethod
    def from_rms(cls, q0: float, H: float, h_rms: float, q1: float = math.inf
                 ) -> SelfAffine:
        """The surface whose rms height over ``q >= q0`` (to infinity) is ``h_rms`` [m].

        ``h_rms^2 = 2 pi int_q0^inf q C dq = pi C0 q0^2 / H``.
        """
        if not (h_rms > 0 and math.isfinite(h_rms)):
            raise InputError(f"h_rms = {h_rms} must be a positive length [m]")
        if not (q0 > 0 and math.isfinite(q0) and q0**2 > 0):
            raise InputError(f"q0 = {q0} must be a positive wavenumber [1/m]")
        return cls(q0, H, H * h_rms**2 / (math.pi * q0**2), q1)

    def C(self, q: Any) -> np.ndarray:
        """The isotropic 2-D spectrum [m^4] at wavenumber ``q`` [1/m]."""
        q = np.asarray(q, dtype=float)
        return np.where(q >= self.q0 * (1 - 1e-12),
                        self.C0 * (q / self.q0) ** (-2.0 * (1.0 + self.H)), 0.0)

    def rms(self, q1: float | None = None) -> float:
        """rms height [m] of the band q0..q1 (default: the surface's q1)."""
        q1 = self.q1 if q1 is None else q1
        h = self.H
        return math.sqrt(math.pi * self.C0 * self.q0**2 / h * (1 - (q1 / self.q0) ** (-2 * h)))

    def rms_slope(self, q1: float | None = None) -> float:
        """rms slope [-] of the band q0..q1 (default: the surface's q1).

        ``<|grad h|^2> = 2 pi int q^3 C dq
        = 2 pi C0 q0^4 ((q1/q0)^(2 - 2H) - 1) / (2 - 2H)``.
        """
        q1 = self.q1 if q1 is None else q1
        k = 2.0 - 2.0 * self.H
        return math.sqrt(2 * math.pi * self.C0 * self.q0**4 * math.expm1(k * math.log(
            q1 / self.q0)) / k)


@dataclass(frozen=True, eq=False)
class TabulatedPSD:
    """A measured 2-D spectrum, interpolated linearly in log q - log C.

    Attributes
    ----------
    q : numpy.ndarray
        Wavenumbers [1/m], increasing.
    C_values : numpy.ndarray
        Spectrum [m^4] (positive).
    """

    q: np.ndarray
    C_values: np.ndarray

    def __post_init__(self) -> None:
        q, c = np.asarray(self.q, float), np.asarray(self.C_values, float)
        if q.size < 2 or q.shape != c.shape or np.any(np.diff(q) <= 0) or np.any(q <= 0):
            raise InputError("a tabulated spectrum needs two or more increasing positive q")
        if np.any(~np.isfinite(c)) or np.any(c <= 0):
            raise InputError("a tabulated spectrum needs positive finite C(q)")

    @property
    def q0(self) -> float:
        """Smallest tabulated wavenumber [1/m]."""
        return float(self.q[0])

    @property
    def q1(self) -> float:
        """Largest tabulated wavenumber [1/m]."""
        return float(self.q[-1])

    def C(self, q: Any) -> np.ndarray:
        """The spectrum [m^4] at ``q`` [1/m] (0 outside the table)."""
        q = np.asarray(q, dtype=float)
        inside = (q >= self.q[0] * (1 - 1e-12)) & (q <= self.q[-1] * (1 + 1e-12))
        lq = np.log(np.clip(q, self.q[0], self.q[-1]))
        val = np.exp(np.interp(lq, np.log(self.q), np.log(self.C_values)))
        return np.where(inside, val, 0.0)

    def rms(self, q1: float | None = None) -> float:
        """rms height [m] of the band q0..q1 (trapezoid in log q)."""
        from scipy.integrate import trapezoid  # numpy < 2 has no np.trapezoid

        q1 = self.q1 if q1 is None else q1
        q = self.q[self.q <= q1]
        return math.sqrt(2 * math.pi * float(trapezoid(q**2 * self.C(q), np.log(q))))

    def rms_slope(self, q1: float | None = None) -> float:
        """rms slope [-] of the band q0..q1 (``2 pi int q^3 C dq``, trapezoid in log q)."""
        from scipy.integrate import trapezoid

        q1 = self.q1 if q1 is None else q1
        q = self.q[self.q <= q1]
        return math.sqrt(2 * math.pi * float(trapezoid(q**4 * self.C(q), np.log(q))))


def asphalt_like(q1: float = 1e6) -> SelfAffine:
    """An asphalt-like road: q0 = 2 pi / 1 cm, H = 0.8, h_rms = 0.3 mm.

    Figures of the order Persson uses for road surfaces (J. Phys.: Condens.
    Matter 17 (2005) R1, Fig. 1 and section 7: asphalt and concrete roads with
    H about 0.8, roll-off near 1 cm, rms of a few tenths of a millimetre).
    """
    return SelfAffine.from_rms(2 * math.pi / 0.01, 0.8, 0.3e-3, q1)


def check_roughness(surface: Any, q1: float) -> float:
    """The rms slope of ``surface`` over q0..q1, refused when the theory cannot take it.

    Persson's theory treats the roughness as a perturbation of small slope on a
    linear-elastic half-space, and its viscoelastic friction grows about as the
    rms slope (on the packaged tread compound and the asphalt-like surface, rms
    slope 1.6 to q1 = 1e6 1/m, the peak mu is 1.6).  Road surfaces measured to
    the scales that matter have rms slopes of order 1.  Above :data:`SLOPE_WARN`
    a :class:`RoughnessWarning` says the result is doubtful; above
    :data:`SLOPE_MAX` (a roughness ten times steeper than 45 degrees, e.g. a
    rms height of centimetres under a roll-off of 1 cm, which would give a
    friction coefficient of order ten or more) the surface is refused.

    Raises
    ------
    InputError
        ``q1`` is not above the surface's ``q0`` (no roughness between them), or the
        rms slope exceeds :data:`SLOPE_MAX` (or is not finite).
    """
    q0 = float(surface.q0)
    if not float(q1) > q0:  # also a NaN
        raise InputError(f"Persson: q1 = {float(q1):.4g} 1/m is not above the surface's "
                         f"roll-off q0 = {q0:.4g} 1/m: expected q1 > q0 (the largest "
                         "wavenumber of the roughness, e.g. 1e6 1/m for road surfaces)")
    slope = float(surface.rms_slope(q1))
    where = (f"q0 = {surface.q0:.4g} to q1 = {q1:.4g} 1/m, rms height {surface.rms(q1):.3g} m")
    if not slope <= SLOPE_MAX:
        raise InputError(f"Persson: the surface's rms slope is {slope:.3g} ({where}); the "
                         "theory takes small slopes on a linear-elastic rubber and road "
                         f"surfaces have slopes of order 1, so above {SLOPE_MAX:g} it is "
                         "refused (check the rms height and its unit, H and q1)")
    if slope > SLOPE_WARN:
        warnings.warn(f"Persson: the surface's rms slope is {slope:.3g} ({where}), steeper "
                      "than road surfaces (order 1); the friction computed for it is "
                      "doubtful (a smaller q1 or rms height is more plausible)",
                      RoughnessWarning, stacklevel=4)
    return slope


def one_d_to_two_d(q: Any, C1: Any, H: Any) -> np.ndarray:
    """2-D spectrum [m^4] from a two-sided 1-D one [m^3] with Hurst exponent ``H``.

    ``C = C1 Gamma(H + 1) / (sqrt(pi) Gamma(H + 1/2) q)``: exact for a
    self-affine isotropic surface (module docstring).
    """
    from scipy.special import gamma

    H = np.clip(np.asarray(H, dtype=float), 0.0, 1.0)
    return (np.asarray(C1, dtype=float) * gamma(H + 1) / (math.sqrt(math.pi) * gamma(H + 0.5))
            / np.asarray(q, dtype=float))


def psd_from_profile(x: Any, h: Any, *, bins_per_decade: int = 10,
                     source: str = "profile") -> TabulatedPSD:
    """The isotropic 2-D spectrum estimated from a 1-D height profile.

    The profile (equally spaced ``x`` [m], heights ``h`` [m]) is detrended
    (straight line removed), Hann-windowed (power restored by the window's
    mean square), Fourier transformed; the two-sided 1-D periodogram
    ``C1(q) = |FFT|^2 dx / (2 pi N)`` is averaged in logarithmic bins, and
    converted to 2-D by :func:`one_d_to_two_d` with the local Hurst exponent of
    the binned spectrum.  The wavenumbers run from ``2 pi / L`` to the Nyquist
    ``pi / dx``.
    """
    x = np.asarray(x, dtype=float).ravel()
    h = np.asarray(h, dtype=float).ravel()
    if x.size != h.size or x.size < 16:
        raise InputError(f"a profile needs x and h of the same length >= 16 (got {x.size}, "
                         f"{h.size})", file=source)
    dxs = np.diff(x)
    dx = float(np.mean(dxs))
    if dx <= 0 or np.max(np.abs(dxs - dx)) > 1e-3 * dx:
        bad = int(np.argmax(np.abs(dxs - dx))) + 2
        raise InputError("x must be increasing with a constant step", file=source,
                         column="x", row=bad)
    n = x.size
    h = h - np.polyval(np.polyfit(x, h, 1), x)
    w = np.hanning(n)
    spec = np.fft.rfft(h * w)
    q = 2 * np.pi * np.fft.rfftfreq(n, dx)
    C1 = np.abs(spec) ** 2 * dx / (2 * np.pi * n * np.mean(w**2))
    q, C1 = q[1:], C1[1:]
    edges = np.logspace(np.log10(q[0]), np.log10(q[-1]) + 1e-9,
                        max(3, int(np.log10(q[-1] / q[0]) * bins_per_decade) + 1))
    idx = np.digitize(q, edges) - 1
    qb, cb = [], []
    for k in range(edges.size - 1):
        sel = idx == k
        if np.any(sel):
            qb.append(float(np.exp(np.mean(np.log(q[sel])))))
            cb.append(float(np.mean(C1[sel])))
    qa, ca = np.array(qb), np.array(cb)
    if qa.size < 3 or np.any(ca <= 0):
        raise InputError("the profile is too short or flat for a spectrum", file=source)
    slope = np.gradient(np.log(ca), np.log(qa))
    H = -(1.0 + slope) / 2.0
    return TabulatedPSD(qa, one_d_to_two_d(qa, ca, H))


def psd_from_profile_csv(path: str | os.PathLike[str], *, x: str = "x", h: str = "h",
                         units: dict[str, str] | None = None, **kw: Any) -> TabulatedPSD:
    """:func:`psd_from_profile` of a CSV with a position and a height column.

    Units come from the headers (``x [mm]``, ``h [um]``) or ``units``; both
    columns are lengths.
    """
    from ._table import read_columns

    d = read_columns(path, {"x": (x, "length"), "h": (h, "length")}, units)
    return psd_from_profile(d["x"], d["h"], source=str(path), **kw)
