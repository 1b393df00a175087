"""A trace that meets P_fin before it has read a face: the face read through the stop.

``core2d.planner.hops.across_wall`` reads the face slid along over the last ``hop`` of the
trace (0.69 eps at sigma 0.3 eps, taxels 0.25 eps). A trace that began at a pass's contact
less than that before the controller stopped on P_fin has no such stretch; it used to be
Case 1 there, whatever P_fin was. With a noisy sensor the face is now read through the
stop's contact too (``through_stop``) and the answer is the map's alone: the far face's
record near P_fin (``against``) must run against the face and lie behind it, or P_fin must.

* ``numerics`` seed 2 at sigma 0.3 eps, taxels 0.25 eps, sensor seed 2002: a trace from a
  pass's contact met P_fin on a needle 0.07 eps thick after three contacts (the first 0.36
  eps from the last); the needle's last 5 eps on both faces were lost (0.9715 covered);
* the rule's readings one by one on a face along y = 0, material below;
* perfect sensing left as it was (``islands`` seed 0 noiselessly).

Coverage is :func:`core2d.truth.metrics.sensor_metrics`'s, against the true outline.
"""
from __future__ import annotations

import numpy as np
import pytest

from core2d import SensorModel, sense_slice
from core2d.planner.hops import across_wall
from core2d.planner.regions import Posture
from core2d.resolution import repeated_reads
from core2d.truth.metrics import sensor_metrics
from outlines import outline
from slicer.contact.exact import ExactContact

# a trace of two readings 0.3 apart along y = 0 (material below), P_fin appended last;
# the stop's contact 0.9 on from the first
_LAST, _NOW = np.array([0.3, 0.0]), np.array([0.9, 0.0])
_PIECES = [np.array([[0.0, 0.0], [0.3, 0.0]])]
_POSE = Posture(np.array([50.0, 2.0]), np.array([-1.0, 0.0]))  # crossing far past the tip
_HOP, _NEAR, _GAP = 0.69, 0.54, 1.0
_BEHIND, _FRONT, _NONE = [[1.1, -0.1]], [[1.1, 0.1]], np.zeros((0, 2))


def _asked(fin, far, through_stop=True, now=_NOW, against=True):
    fin = np.asarray(fin, float)
    record = (lambda face: np.asarray(far, float).reshape(-1, 2)) if against else None
    return across_wall(_PIECES + [fin[None]], _LAST, now, fin, _POSE, 1.0, _HOP, _NEAR, _GAP,
                       record, 1.8, through_stop)


@pytest.mark.parametrize("fin, far, wall", [
    ((1.1, -0.2), _BEHIND, True),  # P_fin and its record behind the face: a wall's far face
    ((1.1, 0.2), _BEHIND, True),  # P_fin read in front, its record behind
    ((1.1, 0.2), _FRONT, False),  # both in front: a slit's far wall
    ((1.1, -0.2), _NONE, False),  # not recorded on a face running against this one
    ((1.1, -0.8), _NONE, False),  # deep behind: a short line does not read the crossing
])
def test_a_short_trace_is_read_through_the_stop_by_the_maps_faces(fin, far, wall):
    assert _asked(fin, far) is wall


def test_a_short_trace_without_the_stop_or_the_map_is_not_across():
    """The rule before (``through_stop`` False), no map, and a stop still within ``hop`` of
    the trace's first contact: Case 1, as before."""
    assert _asked((1.1, -0.2), _BEHIND, through_stop=False) is False
    assert _asked((1.1, -0.2), _BEHIND, against=False) is False
    assert _asked((1.1, -0.2), _BEHIND, now=np.array([0.6, 0.0])) is False


def test_a_pass_contact_near_p_fin_on_a_needle_is_slid_past(monkeypatch):
    """``numerics`` seed 2, sensor seed 2002, sigma 0.3 eps, taxels 0.25 eps: the trace
    from a pass's contact on the needle's upper face met P_fin (read on its lower face)
    after three contacts, 0.36 eps from the first to the last. Through the stop's contact
    (0.96 eps) P_fin read 0.25 eps and the lower face's record 0.11 eps behind the face,
    and the trace slides on round the needle's end. With the face read over the trace
    alone (the rule before) it fails: 0.9715."""
    import core2d.planner.tracing as tracing

    loops = outline("numerics", np.random.default_rng(2), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))
    sensor = lambda: SensorModel.of_eps(1.0, 0.3, 0.25, 2002,  # noqa: E731
                                        reads=repeated_reads(1.0, 0.3, 0.25))

    def sensed():
        res = sense_slice(ExactContact(loops), ws, 1.0, max_motions=20000, sensor=sensor())
        return res, sensor_metrics(loops, res, 1.0, sensor().noise)

    res, m = sensed()
    assert not res.stats.budget_hit
    assert m["coverage_sensor"] >= 0.98, f"coverage {m['coverage_sensor']:.4f}"
    assert m["precision_sensor"] >= 0.98
    assert m["w3_unsound_count_sensor"] == 0
    before = tracing.across_wall
    monkeypatch.setattr(tracing, "across_wall", lambda *a: before(*a[:11], False))
    assert sensed()[1]["coverage_sensor"] < 0.98


def test_perfect_sensing_is_left_as_it_was(monkeypatch):
    """Noiselessly a trace shorter than ``hop`` is not read through the stop: a perfect
    sensor's P_fin tells its side itself. ``islands`` seed 0 noiselessly: the same run as
    with the rule before (1,314 motions); read through the stop, one call is answered
    otherwise and the run takes a motion more, for the same coverage."""
    import core2d.planner.tracing as tracing
    from core2d.truth.metrics import slice_metrics

    loops = outline("islands", np.random.default_rng(0), 1.0)
    pts = np.concatenate(loops)
    lo, hi = pts.min(0), pts.max(0)
    ws = ((lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2 + 1.0))

    def sensed():
        res = sense_slice(ExactContact(loops), ws, 1.0, max_motions=20000)
        return res.stats.motions, slice_metrics(loops, res, 1.0)["coverage"]

    now = sensed()
    before = tracing.across_wall
    monkeypatch.setattr(tracing, "across_wall", lambda *a: before(*a[:11], False))
    assert sensed() == now  # the rule before, to the motion
    monkeypatch.setattr(tracing, "across_wall", lambda *a: before(*a[:11], True))
    forced = sensed()
    assert forced[0] != now[0] and forced[1] >= now[1] - 1e-9, (forced, now)
