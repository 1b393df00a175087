"""Lids read again: a noisy sensor's second reading of an opening already probed.

§4.4 escapes an area that repeats an ancestor's A_i and B_i. With a noisy sensor the
ends of a lid are readings, and the same gap's lid comes back through another chain
of splits, no ancestor of the first, its ends other readings of the same two contacts
a few tenths of eps off. The revisit then makes its passes again (a spread and up to
a sweep's worth), which found nothing new the first time.

:func:`repeats_opening` finds such a repeat of a lid closed ``open`` (its passes found
nothing new and one left through it: an opening to F, §3.2), whose ends lie each
within the same-contact radius eps/2 + jitter of the new lid's same end (the same
orientation: the reversed lid has V_i on the other side). The new lid is closed
``open`` too, without passes. Lids left ``unknown`` are looked at again: closing their
repeats the same way lost coverage (keyed sensor study at sigma 0.1 eps, six seeds:
4 slice runs up, 46 down), their second passes' touches closing W2 what the first
left open.

>>> import numpy as np
>>> from types import SimpleNamespace
>>> from core2d.resolution import Resolution
>>> run = SimpleNamespace(res=Resolution.of(1.0, noise=0.1),
...                       openings=[(np.array([0.0, 0.0]), np.array([20.0, 0.0]))])
>>> repeats_opening(run, SimpleNamespace(a=np.array([0.5, 0.4]), b=np.array([19.4, -0.3])))
True
>>> repeats_opening(run, SimpleNamespace(a=np.array([20.0, 0.0]), b=np.array([0.0, 0.0])))
False
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["repeats_opening"]


def repeats_opening(run: Exploration, area) -> bool:
    """Does A_i -> B_i repeat a lid of ``run.openings`` (closed ``open`` by the
    revisit), each end within eps/2 + jitter of its same end? False with a
    perfect sensor, whose runs stay as they were.

    On the ``islands`` outline seed 1 at sigma 0.1 eps (keyed sensor seed 2001) lids
    across the gaps between the islands came back up to three times, each probed by
    32 - 54 passes again: 3,326 motions against 1,769 noiseless (at a84c8f6)."""
    if run.res.jitter == 0:
        return False
    r = run.res.tip_zone
    return any(np.hypot(*(a - area.a)) <= r and np.hypot(*(b - area.b)) <= r
               for a, b in run.openings)
