"""Signal processing of a record: zero-phase low-pass filter, cut-off, steady window.

Filter
    A Butterworth low-pass of order ``order`` applied forwards and backwards
    (:func:`scipy.signal.sosfiltfilt`): no phase shift, so the start-up peak
    and the motor stop stay where they are, and a constant level passes
    unchanged (the mean over a window away from the record ends is preserved).

Automatic cut-off (:func:`auto_cutoff`)
    From the power spectrum of the raw torque (:func:`spectrum`, 0.5 Hz bands):

    1. the broadband noise floor is the median spectral density over the upper
       half of the band (robust to narrow peaks);
    2. narrow-band disturbances (mains hum, rig vibration at a natural
       frequency) are the spectral peaks that stand more than ``10 dB`` above
       their neighbourhood and more than ``auto_snr`` times above the floor;
    3. the signal band ends where the smoothed spectrum first falls to
       ``auto_snr`` times the floor;
    4. the cut-off is the end of the signal band, but at most 0.7 times the
       lowest disturbance, clamped to ``[auto_min, auto_max]``
       (``auto_max = 0`` means a quarter of the sampling rate).

    The record's friction level, start-up peak and stop are slow compared
    with the cut-off; averaging over the steady window removes what is left of
    the noise, so the cut-off mainly matters for window detection and plots.

Steady window (:func:`find_window`)
    1. *At speed*: every speed channel that moves is within ``speed_tolerance``
       of its plateau (the median of the samples above half its peak); the
       longest such stretch is the sliding segment (a channel whose peak is
       under 1 rpm or under 5 % of the other's is a fixed disc or pin).  With
       a rotating pin both motors must be at speed, so the step when the second motor starts and
       stops is excluded.  Without moving speed channels the whole record is
       the segment and the torque alone decides.
    2. ``steady`` mode: the steady level ``L`` is the median of the filtered
       friction coefficient over the second half of the segment; the smoothed
       signal (moving average over ``smooth``) counts as steady while within
       ``max(level_tolerance * |L|, noise_factor * robust std)`` of ``L``.  The
       window starts ``settle`` after the last sample of the first half outside
       the tighter band ``max(start_tolerance * |L|, noise_factor * robust
       std)`` (the tail of the start-up peak), and ends at the first excursion
       from the wider band in the second half (or the end of the segment) minus
       ``end_margin``.
    3. ``initial`` mode (abrasive surfaces, where debris makes the reading
       decay): the window starts ``initial_delay`` after the motors reach speed
       and lasts ``initial_duration``.
    4. A window shorter than ``min_window`` means "no steady window"; a level
       below ``min_mu`` or within ``noise_factor`` times its own scatter means
       "no friction" (pin not in contact, or offsets wrong).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np
from scipy import signal as _sig
from scipy.ndimage import uniform_filter1d

from ..base.errors import InputError
from .rig import FilterSettings, WindowSettings

__all__ = ["lowpass", "auto_cutoff", "spectrum", "CutoffInfo", "find_window", "Window",
           "speed_segment", "NoWindow"]


class NoWindow(Exception):
    """No usable window could be found (the message says why)."""


def lowpass(x: np.ndarray, fs: float, cutoff: float, order: int = 4) -> np.ndarray:
    """Zero-phase Butterworth low-pass of ``x`` sampled at ``fs`` [Hz].

    Parameters
    ----------
    x : numpy.ndarray
        Signal (1-D), or a 2-D array filtered along its last axis.
    fs : float
        Sampling rate [Hz].
    cutoff : float
        Cut-off frequency [Hz] (-3 dB of each pass; about -6 dB overall).
    order : int
        Butterworth order of each pass.

    Returns
    -------
    numpy.ndarray
        Filtered signal, same shape.
    """
    nyq = 0.5 * fs
    if not 0 < cutoff < nyq:
        raise InputError(f"filter cut-off {cutoff:g} Hz must be between 0 and the Nyquist "
                         f"frequency {nyq:g} Hz (sampling rate {fs:g} Hz)")
    sos, zi = _sos(float(cutoff), float(fs), int(order))
    x = np.asarray(x, dtype=float)
    n = x.shape[-1]
    padlen = min(n - 1, 3 * (2 * len(sos) + 1))
    if x.ndim != 1 or padlen < 1:
        return _sig.sosfiltfilt(sos, x, axis=-1, padlen=padlen)
    # what sosfiltfilt does (odd extension, forward and backward passes started at
    # steady state), with the initial state of the sections cached per filter
    ext = np.concatenate((2 * x[0] - x[padlen:0:-1], x, 2 * x[-1] - x[-2:-padlen - 2:-1]))
    y, _ = _sig.sosfilt(sos, ext, zi=zi * ext[0])
    y = y[::-1]
    y, _ = _sig.sosfilt(sos, y, zi=zi * y[0])
    return y[::-1][padlen:-padlen]


_SOS_CACHE: dict[tuple[float, float, int], tuple[np.ndarray, np.ndarray]] = {}


def _sos(cutoff: float, fs: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Second-order sections of the Butterworth low-pass and their steady-state state."""
    key = (round(cutoff, 9), round(fs, 6), order)
    hit = _SOS_CACHE.get(key)
    if hit is None:
        sos = _sig.butter(order, cutoff, btype="low", fs=fs, output="sos")
        hit = (sos, _sig.sosfilt_zi(sos))
        if len(_SOS_CACHE) < 256:
            _SOS_CACHE[key] = hit
    return hit


@dataclass(frozen=True)
class CutoffInfo:
    """How an automatic cut-off was chosen (all frequencies in Hz)."""

    cutoff: float
    signal_edge: float
    noise_floor: float
    disturbances: tuple[float, ...]
    limited_by: str


def auto_cutoff(x: np.ndarray, fs: float, settings: FilterSettings | None = None) -> CutoffInfo:
    """Choose a low-pass cut-off from the spectrum of ``x`` (see the module docstring).

    Parameters
    ----------
    x : numpy.ndarray
        The raw torque signal.
    fs : float
        Sampling rate [Hz].
    settings : FilterSettings, optional
        ``auto_min``, ``auto_max`` and ``auto_snr`` are used.

    Returns
    -------
    CutoffInfo
    """
    st = settings or FilterSettings()
    x = np.asarray(x, dtype=float)
    hi = st.auto_max if st.auto_max > 0 else 0.25 * fs
    hi = min(hi, 0.45 * fs)
    lo = min(st.auto_min, hi)
    f, pxx = spectrum(x, fs)
    if f.size < 8 or not np.any(pxx > 0):
        return CutoffInfo(hi, hi, 0.0, (), "flat spectrum")
    upper = f >= 0.5 * f[-1]
    floor = float(np.median(pxx[upper]))
    if floor <= 0:
        floor = float(np.min(pxx[pxx > 0]))
    logp = np.log10(np.maximum(pxx, floor * 1e-6))
    # narrow-band disturbances: prominent peaks well above the floor
    df = f[1] - f[0]
    width = max(3, int(round(2.0 / df)))
    peaks, _ = _sig.find_peaks(logp, prominence=1.0, wlen=4 * width + 1)
    dist = [float(f[i]) for i in peaks
            if f[i] >= lo and pxx[i] > st.auto_snr * floor and f[i] < 0.5 * fs * 0.98]
    # signal edge: where the smoothed spectrum (peaks removed) first meets snr * floor
    smooth = _median_smooth(logp, width)
    above = smooth > np.log10(st.auto_snr * floor)
    start = int(np.searchsorted(f, lo * 0.5))
    below = np.flatnonzero(~above[start:])
    edge = float(f[start + below[0]]) if below.size else float(f[-1])
    cutoff = max(edge, lo)
    limited = "signal band"
    if dist:
        cap = 0.7 * min(dist)
        if cap < cutoff:
            cutoff, limited = cap, f"disturbance at {min(dist):.4g} Hz"
    if cutoff < lo:
        cutoff, limited = lo, "auto_min"
    if cutoff > hi:
        cutoff, limited = hi, "auto_max"
    return CutoffInfo(float(cutoff), edge, floor, tuple(dist), limited)


def spectrum(x: np.ndarray, fs: float, resolution: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Power spectral density of ``x`` (Hann-windowed periodogram, band-averaged).

    One FFT of the whole record, then the periodogram is averaged over blocks
    of bins ``resolution`` Hz wide (Bartlett smoothing in frequency): about the
    variance of a Welch estimate with ``1 / resolution`` s segments, at the
    cost of a single FFT.

    Returns
    -------
    f : numpy.ndarray
        Block-centre frequencies [Hz].
    pxx : numpy.ndarray
        Power spectral density [unit^2 / Hz].
    """
    from scipy import fft as _fft

    x = np.asarray(x, dtype=float)
    n = x.size
    win = _hann(n)
    y = (x - x.mean()) * win
    p = np.abs(_fft.rfft(y)) ** 2 * (2.0 / (fs * float(np.sum(win * win))))
    df = fs / n
    k = max(1, int(round(resolution / df)))
    m = (p.size - 1) // k
    if m < 1:
        return np.fft.rfftfreq(n, 1.0 / fs), p
    blocks = p[1 : 1 + m * k].reshape(m, k).mean(axis=1)
    freqs = (np.arange(m) * k + 1 + (k - 1) / 2.0) * df
    return freqs, blocks


@functools.lru_cache(maxsize=16)
def _hann_cached(n: int) -> np.ndarray:
    w = np.hanning(n)
    w.setflags(write=False)
    return w


def _hann(n: int) -> np.ndarray:
    return _hann_cached(n)


def _median_smooth(y: np.ndarray, width: int) -> np.ndarray:
    from scipy.ndimage import median_filter

    return median_filter(y, size=2 * width + 1, mode="nearest")


@dataclass(frozen=True)
class Window:
    """A window of a record, as sample indices ``[start, stop)``."""

    start: int
    stop: int
    segment: tuple[int, int]
    level: float | None = None
    tolerance: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    def slice(self) -> slice:
        return slice(self.start, self.stop)


def _longest_run(mask: np.ndarray) -> tuple[int, int] | None:
    if not mask.any():
        return None
    m = np.concatenate(([False], mask, [False])).astype(np.int8)
    d = np.diff(m)
    starts = np.flatnonzero(d == 1)
    stops = np.flatnonzero(d == -1)
    k = int(np.argmax(stops - starts))
    return int(starts[k]), int(stops[k])


#: A speed channel whose peak is below this [rad/s] (1 rpm), or below 5 % of the
#: fastest channel's peak, does not move.
MOVING = 2.0 * np.pi / 60.0


def speed_segment(speeds: list[np.ndarray], tolerance: float, step: int = 1
                  ) -> tuple[int, int, list[str]]:
    """The longest stretch where every moving speed channel is at its plateau.

    Parameters
    ----------
    speeds : list of numpy.ndarray
        Filtered speed channels [rad/s] (disc, pin).
    tolerance : float
        Relative tolerance around each plateau.
    step : int
        Look at every ``step``-th sample only (the speeds are smoothed, so a
        few milliseconds of resolution are plenty); indices are returned at
        the full rate, the segment shrunk inwards to whole steps.

    Returns
    -------
    start, stop : int
        Sample indices ``[start, stop)``.
    notes : list of str
        Remarks (e.g. "speeds constant: segment from the torque only").

    Raises
    ------
    NoWindow
        When the pin and disc never move relative to each other, or the
        channels are never at speed together.
    """
    n = speeds[0].size
    k = max(1, int(step))
    speeds = [np.asarray(w)[::k] for w in speeds]
    rel = np.abs(speeds[1] - speeds[0]) if len(speeds) > 1 else np.abs(speeds[0])
    if float(np.max(rel)) < MOVING:
        raise NoWindow("no sliding: the relative speed of pin and disc never exceeds 1 rpm")
    mask = np.ones(speeds[0].size, dtype=bool)
    notes: list[str] = []
    peaks = [float(np.max(np.abs(w))) for w in speeds]
    top = max(peaks)
    for w, peak in zip(speeds, peaks, strict=True):
        if peak < MOVING or peak < 0.05 * top:
            continue  # a fixed disc or pin (its reading is noise)
        a = np.abs(w)
        plateau = float(np.median(a[a >= 0.5 * peak]))
        mask &= np.abs(a - plateau) <= tolerance * plateau
    run = _longest_run(mask)
    if run is None:
        raise NoWindow("the pin and disc motors are never at their plateau speeds together")
    run = (run[0] * k, min(n, run[1] * k - (k - 1)))  # back to full-rate sample indices
    if run == (0, n) or (run[0] == 0 and run[1] >= n - k):
        notes.append("speeds at their plateau over the whole record: the window is found "
                     "from the torque alone")
    return run[0], run[1], notes


def find_window(
    mu: np.ndarray,
    fs: float,
    segment: tuple[int, int],
    settings: WindowSettings,
    mode: str = "steady",
) -> Window:
    """Find the steady sliding window in a filtered friction signal.

    Parameters
    ----------
    mu : numpy.ndarray
        Filtered friction coefficient (offsets subtracted).
    fs : float
        Sampling rate [Hz].
    segment : (int, int)
        The sliding segment ``[a, b)`` from :func:`speed_segment`.
    settings : WindowSettings
        Tolerances and margins (see the module docstring).
    mode : {"steady", "initial"}
        ``initial`` for abrasive surfaces (only the first seconds are valid).

    Returns
    -------
    Window

    Raises
    ------
    NoWindow
        When no window of at least ``min_window`` can be found, or the steady
        level is not positive.
    """
    if mode == "initial":
        return _initial_window(mu, fs, segment, settings)
    if mode != "steady":
        raise ValueError(f"mode must be 'steady' or 'initial', not {mode!r}")
    return _steady_window(mu, fs, segment, settings)


def _min_length(st: WindowSettings, fs: float) -> int:
    """The shortest accepted window, in samples."""
    return max(2, int(round(st.min_window * fs)))


def _initial_window(mu: np.ndarray, fs: float, segment: tuple[int, int],
                    st: WindowSettings) -> Window:
    """The fixed window ``initial_delay .. + initial_duration`` after the motors reach speed."""
    a, b = segment
    min_len = _min_length(st, fs)
    s0 = a + int(round(st.initial_delay * fs))
    e0 = s0 + int(round(st.initial_duration * fs))
    limit = b - int(round(st.end_margin * fs))
    notes: list[str] = []
    if e0 > limit:
        e0 = limit
        notes.append("initial window shortened: the motors stop earlier")
    if e0 - s0 < min_len:
        raise NoWindow(
            f"no initial window: the motors are at speed for {(b - a) / fs:.3g} s, "
            f"need initial_delay {st.initial_delay:g} s + at least min_window "
            f"{st.min_window:g} s")
    seg = mu[s0:e0]
    level = float(np.mean(seg))
    _check_friction(level, seg, st, "the initial window")
    x = np.arange(seg.size) - 0.5 * (seg.size - 1)
    drift = float(np.dot(x, seg - level) / np.dot(x, x)) * seg.size / level
    if abs(drift) > st.level_tolerance:
        notes.append(f"the friction drifts by {100 * drift:+.1f} % across the initial "
                     "window (start-up peak not over, or debris): check initial_delay "
                     "and initial_duration")
    return Window(s0, e0, segment, level, None, tuple(notes))


def _steady_window(mu: np.ndarray, fs: float, segment: tuple[int, int],
                   st: WindowSettings) -> Window:
    """The longest stretch, ending in the second half, where the friction stays at its level."""
    a, b = segment
    min_len = _min_length(st, fs)
    if b - a < 2 * min_len:
        raise NoWindow(f"no steady window: the motors are at speed for only {(b - a) / fs:.3g} "
                       f"s (need at least 2 x min_window = {2 * st.min_window:g} s)")
    h = a + (b - a) // 2
    margin = int(round(st.end_margin * fs))
    ref_stop = max(h + min_len // 2, b - margin)
    k = max(1, int(fs // 200))  # robust statistics of the smooth filtered signal from 200 Hz
    level = float(np.median(mu[h:ref_stop:k]))
    _check_friction(level, mu[h:ref_stop:k], st, "the second half of sliding")
    m = max(1, int(round(st.smooth * fs)))
    avg = uniform_filter1d(mu[a:b], size=m, mode="nearest")
    ref = avg[h - a:ref_stop - a:k]
    spread = 1.4826 * float(np.median(np.abs(ref - level)))
    tol = max(st.level_tolerance * abs(level), st.noise_factor * spread)
    dev = np.abs(avg - level) > tol
    tol_start = max(min(st.start_tolerance, st.level_tolerance) * abs(level),
                    st.noise_factor * spread)
    first = np.flatnonzero(np.abs(avg[: h - a] - level) > tol_start)
    s0 = a + (int(first[-1]) + 1 if first.size else 0) + int(round(st.settle * fs))
    later = np.flatnonzero(dev[h - a:])
    e0 = (h + int(later[0])) if later.size else b
    e0 -= margin
    notes = []
    if later.size:
        notes.append(f"window ends {(b - h - int(later[0])) / fs:.3g} s before the motors "
                     "leave their plateau: the friction leaves the steady band")
    if e0 - s0 < min_len:
        raise NoWindow(
            f"no steady window: the friction stays within +/-{tol:.3g} of its level "
            f"{level:.3g} for only {max(e0 - s0, 0) / fs:.3g} s (min_window "
            f"{st.min_window:g} s)")
    return Window(int(s0), int(e0), segment, level, float(tol), tuple(notes))


def _check_friction(level: float, values: np.ndarray, st: WindowSettings, where: str) -> None:
    """Raise NoWindow when ``level`` is below ``min_mu`` or not clear of the noise."""
    if level >= st.min_mu and level > 10 * st.noise_factor * float(np.std(values)):
        return  # clearly friction: skip the robust (slower) check
    spread = 1.4826 * float(np.median(np.abs(values - np.median(values))))
    if level < st.min_mu or level < st.noise_factor * spread:
        raise NoWindow(
            f"no friction: mu = {level:.3g} in {where} is below min_mu = {st.min_mu:g} or "
            f"within {st.noise_factor:g} x its scatter ({spread:.2g}): pin not in contact, or "
            "offsets wrong?")
