"""Online detection of softening episodes while the pipe goes down (event snapshots).

The detector applies, record by record, the very definition of a softening episode that
:func:`onbottom.dem.summary.softening_episodes` applies to a finished run: the V–w record is
averaged in bins of w/D (``step``, the summary's bin width, 0.005 by default: the "light
smoothing" that keeps the step-to-step force-chain noise from triggering), and an episode is a
fall of the bin-mean curve more than ``drop_fraction`` (5 % by default) below its running peak
that lasts until the curve climbs back above that peak (or the record ends). Streaming the bin
means through :meth:`SofteningDetector.add_bin` therefore finds exactly the episodes the summary
finds on the same record with the same ``step`` and ``drop_fraction`` (tested).

What :func:`onbottom.dem.experiment.penetrate` does with the detector's answers:

* each bin gets one *candidate* field snapshot, taken at the first record at or past the bin
  centre (one per ``step``·D of travel: the throttle);
* a bin that becomes the running peak makes its candidate the peak candidate; a bin that becomes
  the lowest point of a drop makes its candidate the trough candidate;
* the peak candidate is committed (stored in the result) when the drop is confirmed, i.e. as soon
  as a bin mean lies more than ``drop_fraction`` below the peak;
* the trough candidate is committed when the episode ends: the curve climbs back above the peak,
  or the run reaches its final embedment. The trough is the lowest bin of the whole episode (the
  summary's definition), so it cannot be committed on an earlier rise.

Nothing in here touches the particles; the detector's state is a small dict of floats that goes
into the checkpoint's JSON metadata (exact: JSON writes floats with ``repr``).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from onbottom import _validate as _v

__all__ = ["DEFAULT_EVENT_STEP", "DEFAULT_MAX_EVENT_SNAPSHOTS", "SofteningDetector"]

DEFAULT_EVENT_STEP = 0.005
"""Bin width in w/D of the smoothing the detector applies (the summary's default bin)."""

DEFAULT_MAX_EVENT_SNAPSHOTS = 64
"""Cap on the stored event snapshots of one run (a full-size snapshot is about 2.5 MB)."""

# actions returned by add_bin / finish
NEW_PEAK = "new_peak"
NEW_TROUGH = "new_trough"
CONFIRM = "confirm"
END = "end"


@dataclass
class SofteningDetector:
    """Streaming softening-episode detector on the bin means of a V–w record.

    Parameters
    ----------
    step : float
        Bin width in w/D [-], > 0.
    drop_fraction : float
        Smallest relative drop below the running peak that makes an episode [-], in (0, 1).

    Feed raw records with :meth:`push` (it bins them and returns the actions of every bin it
    closes) or bin means with :meth:`add_bin`; call :meth:`finish` at the end of the run.
    ``episodes`` lists the finished episodes as (w_peak, w_trough, v_peak, v_trough), w at the
    bin centres [-].
    """

    step: float = DEFAULT_EVENT_STEP
    drop_fraction: float = 0.05
    # open bin of the raw records
    bin: int = -1
    total: float = 0.0
    count: int = 0
    # episode state (w/D at bin centres, bin means)
    peak_w: float | None = None
    peak_v: float | None = None
    trough_w: float | None = None
    trough_v: float | None = None
    descending: bool = False
    confirmed: bool = False
    episodes: list[list[float]] = field(default_factory=list)

    def __post_init__(self) -> None:
        _v.positive("event_step", self.step)
        _v.in_range(
            "event_drop_fraction",
            self.drop_fraction,
            0.0,
            1.0,
            low_inclusive=False,
            high_inclusive=False,
        )

    # ---- binning of raw records ----------------------------------------------------------
    def bin_of(self, w_over_d: float) -> int:
        """Index of the bin holding ``w_over_d`` (the summary's ``int(w/D / step)``)."""
        return int(w_over_d / self.step)

    def centre(self, k: int) -> float:
        """Centre of bin ``k`` in w/D [-]."""
        return (k + 0.5) * self.step

    def push(self, w_over_d: float, v: float) -> list[tuple[str, int]]:
        """Add one record; return the actions (name, bin) of the bin it closes, if any.

        Records with w < 0 or a non-finite V are skipped, as in the summary's binning.
        """
        if not (w_over_d >= 0.0) or v != v or v in (float("inf"), float("-inf")):
            return []
        k = self.bin_of(w_over_d)
        out: list[tuple[str, int]] = []
        if k != self.bin:
            out = self.close_bin()
            self.bin, self.total, self.count = k, 0.0, 0
        self.total += v
        self.count += 1
        return out

    def close_bin(self) -> list[tuple[str, int]]:
        """Close the open bin (if it holds records) and feed its mean to :meth:`add_bin`."""
        if self.count == 0:
            return []
        k = self.bin
        mean = self.total / self.count
        self.count = 0
        self.total = 0.0
        return [(a, k) for a in self.add_bin(self.centre(k), mean)]

    # ---- the episode state machine (summary.softening_episodes, streamed) -----------------
    def add_bin(self, w: float, f: float) -> list[str]:
        """Feed the next bin mean ``f`` at ``w``; return the actions it triggers, in order.

        ``new_peak``: this bin is the running peak; ``new_trough``: this bin is the lowest
        point of the current drop; ``confirm``: the drop of the current episode just exceeded
        ``drop_fraction`` (the peak is final); ``end``: the current confirmed episode ended
        (appended to ``episodes``) before this bin became the new peak.
        """
        acts: list[str] = []
        if self.peak_v is None:
            self.peak_w, self.peak_v = w, f
            return [NEW_PEAK]
        if not self.descending:
            if f >= self.peak_v:
                self.peak_w, self.peak_v = w, f
                return [NEW_PEAK]
            self.descending = True
            self.trough_w, self.trough_v = w, f
            acts.append(NEW_TROUGH)
        elif f <= self.peak_v:
            assert self.trough_v is not None
            if f < self.trough_v:
                self.trough_w, self.trough_v = w, f
                acts.append(NEW_TROUGH)
        else:  # back above the peak: the episode is over
            acts.extend(self.finish())
            self.peak_w, self.peak_v = w, f
            acts.append(NEW_PEAK)
            return acts
        assert self.trough_v is not None
        if (
            not self.confirmed
            and self.peak_v > 0.0
            and self.trough_v < (1.0 - self.drop_fraction) * self.peak_v
        ):
            self.confirmed = True
            acts.append(CONFIRM)
        return acts

    def finish(self) -> list[str]:
        """End the current drop (record end or climb-back); ``["end"]`` if it was an episode."""
        acts: list[str] = []
        if self.descending and self.confirmed:
            self.episodes.append([self.peak_w, self.trough_w, self.peak_v, self.trough_v])
            acts.append(END)
        self.descending = False
        self.confirmed = False
        self.trough_w = self.trough_v = None
        return acts

    # ---- checkpoint --------------------------------------------------------------------
    def state(self) -> dict:
        """JSON-able state (exact round trip through ``json``)."""
        return asdict(self)

    @classmethod
    def from_state(cls, state: dict) -> SofteningDetector:
        """The detector saved by :meth:`state`."""
        return cls(**state)
