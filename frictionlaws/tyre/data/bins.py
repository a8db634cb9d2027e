"""The blocks of a sweep: consecutive samples averaged along the curves of the slip and
the forces, with each block's pass and direction, the force lag that makes the up and down
passes meet, and the curvature correction of the block means (used by
:func:`frictionlaws.tyre.data.segments.prepare_run`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["blocks", "SweepBins", "BINS_PER_SWEEP", "MIN_BLOCK", "MAX_LAG_S", "CURVED_SHARE",
           "SPLITS"]

#: Blocks per pass of a sweep over its range (averages of consecutive samples).
BINS_PER_SWEEP = 40
#: The fewest samples a block averages (fewer, at the end of a direction: dropped).
MIN_BLOCK = 3
#: The longest force lag behind the slip taken [s].
MAX_LAG_S = 0.5
#: A block whose mean the curvature of a curve moves by more than this share of the curve's
#: range is halved (:meth:`SweepBins.split_curved`), at most :data:`SPLITS` times.
CURVED_SHARE = 0.001
SPLITS = 3


def blocks(x: np.ndarray, direction: np.ndarray, steps: list[np.ndarray],
            spans: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """A block number per sample (-1: too few to average) and its pass (a stretch of one
    direction): consecutive samples of one pass, each block :data:`MIN_BLOCK` samples or
    more and about 1 / :data:`BINS_PER_SWEEP` of a pass along the curves of the slip and
    the forces (each scaled by its range): short where a force changes fast (the steep rise,
    a sharp aligning-moment peak), long where the curves are flat."""
    span_x = float(np.ptp(x)) or 1.0
    arc2 = np.diff(x, prepend=x[0]) ** 2 / span_x ** 2
    for step, span in zip(steps, spans):
        arc2 = arc2 + (step / span) ** 2
    arc = np.sqrt(arc2)
    turns = np.flatnonzero(np.diff(direction) != 0) + 1
    passes = np.split(np.arange(x.size), turns)
    traversed = sum(float(np.ptp(x[p])) for p in passes) / span_x
    length = float(arc.sum()) / max(traversed, 1.0) / BINS_PER_SWEEP
    block = np.full(x.size, -1)
    piece = np.zeros(x.size, dtype=int)
    number = 0
    for k, p in enumerate(passes):
        piece[p] = k
        count, since = 0, 0.0
        for i in p:
            if count >= MIN_BLOCK and since >= length:
                number, count, since = number + 1, 0, 0.0
            block[i] = number
            count += 1
            since += arc[i]
        if count < MIN_BLOCK:
            block[p[-count:]] = -1 if number == 0 or block[p[0]] == number else number - 1
        number += 1
    return block, piece


@dataclass
class SweepBins:
    """The blocks of one sweep: each block's pass and direction, the slip's moments."""

    block: np.ndarray
    x: np.ndarray
    sign: np.ndarray
    piece: np.ndarray

    def __post_init__(self) -> None:
        ids, self.inverse, self.counts = np.unique(self.block, return_inverse=True,
                                                   return_counts=True)
        self.direction = np.zeros(ids.size)
        self.direction[self.inverse] = self.sign
        self.passes = np.zeros(ids.size, dtype=int)
        self.passes[self.inverse] = self.piece
        self.xm = self.mean(self.x)

    def mean(self, values: np.ndarray) -> np.ndarray:
        return np.bincount(self.inverse, weights=values) / self.counts

    def lag(self, force: np.ndarray, rate: np.ndarray) -> float:
        """The lag tau [s] that makes the up and down blocks of ``force + tau d force/dt``
        meet (least squares; the down curve interpolated at the up blocks' slips, the ends
        of the sweep left out; 0 when negative or undetermined)."""
        f, r = self.mean(force), self.mean(rate)
        up, down = np.flatnonzero(self.direction > 0), np.flatnonzero(self.direction < 0)
        if up.size < 5 or down.size < 5:
            return 0.0
        order = down[np.argsort(self.xm[down])]
        lo, hi = self.xm[order[0]], self.xm[order[-1]]
        inner = up[(self.xm[up] > lo + 0.1 * (hi - lo)) & (self.xm[up] < hi - 0.1 * (hi - lo))]
        if inner.size < 3:
            return 0.0
        gap = f[inner] - np.interp(self.xm[inner], self.xm[order], f[order])
        step = r[inner] - np.interp(self.xm[inner], self.xm[order], r[order])
        denominator = float(np.sum(step * step))
        if not denominator > 0:
            return 0.0
        return float(np.clip(-np.sum(gap * step) / denominator, 0.0, MAX_LAG_S))

    def variance(self) -> np.ndarray:
        """The spread of the slip within each block (its variance)."""
        return np.maximum(self.mean(self.x * self.x) - self.xm * self.xm, 0.0)

    def second(self, means: np.ndarray, ends: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """F'' at each block from its neighbouring blocks of the same pass (at the ends of a
        pass NaN, or with ``ends`` the next block's) and whether those neighbours are
        distinct (each as far from it as twice its own spread of slip or farther)."""
        sd = np.sqrt(self.variance())
        out = np.full(means.size, np.nan)
        apart = np.zeros(means.size, dtype=bool)
        for k in np.unique(self.passes):
            idx = np.flatnonzero(self.passes == k)
            idx = idx[np.argsort(self.xm[idx])]
            if idx.size < 3:
                continue
            x0, x1, x2 = self.xm[idx[:-2]], self.xm[idx[1:-1]], self.xm[idx[2:]]
            y0, y1, y2 = means[idx[:-2]], means[idx[1:-1]], means[idx[2:]]
            with np.errstate(divide="ignore", invalid="ignore"):
                out[idx[1:-1]] = 2 * ((y2 - y1) / (x2 - x1) - (y1 - y0) / (x1 - x0)) / (x2 - x0)
            apart[idx[1:-1]] = np.minimum(x1 - x0, x2 - x1) >= 2 * sd[idx[1:-1]]
            if ends:
                out[idx[[0, -1]]] = out[idx[[1, -2]]]
        return out, apart

    def curvature(self, means: np.ndarray) -> np.ndarray:
        """Block means moved to the value at the block's mean slip: minus F'' var(x) / 2,
        F'' from the neighbouring blocks of the same pass (the ends, and blocks closer to a
        neighbour than twice their own spread of slip, left as they are)."""
        second, apart = self.second(means)
        ok = apart & np.isfinite(second)
        return means - np.where(ok, second, 0.0) * self.variance() / 2

    def split_curved(self, values: list[np.ndarray], spans: list[float]) -> SweepBins:
        """These blocks with those halved (up to :data:`SPLITS` times) whose mean the
        curvature of one of ``values`` (per sample, with its range in ``spans``) moves by
        more than :data:`CURVED_SHARE` of its range (F'' var / 2, F'' from the neighbours,
        at the ends of a pass the next block's, :meth:`second`), while :data:`MIN_BLOCK`
        samples or more are left in each half.

        A block over a peak much narrower than the blocks around it (the residual aligning
        torque's, some 0.3 deg wide near zero slip angle) averages the peak away, and the
        curvature its neighbours give (:meth:`curvature`) makes up only part of it: a fit
        of such rows finds the peak too wide.  Cut, the peak's blocks are a few samples
        long and their curvature small."""
        b = self
        for _ in range(SPLITS):
            moved = np.zeros(b.counts.size)
            for v, span in zip(values, spans):
                second, _ = b.second(b.mean(v), ends=True)
                moved = np.fmax(moved, np.abs(second) * b.variance() / (2 * span))
            cut = (moved > CURVED_SHARE) & (b.counts >= 2 * MIN_BLOCK)
            if not cut.any():
                break
            position = np.arange(b.x.size) - np.searchsorted(b.inverse, b.inverse)
            late = cut[b.inverse] & (position >= b.counts[b.inverse] // 2)
            b = SweepBins(2 * b.inverse + late, b.x, b.sign, b.piece)
        return b
