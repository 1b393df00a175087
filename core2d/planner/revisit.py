"""A second look at dead ends, with everything the robot has recorded.

An area that reached a dead end in the paper's flow (no Theorem 1 pass into
G_i cap V_i, a pass that found no new contact, or Area(G_i) = 0 while lines
still cross the lid) is *deferred*, never W3 on the spot: those dead ends
say that the recorded postures leave no pass, not that none exists. Once
nothing else is left, every deferred area A_iB_i is looked at again against
the robot's own map (:class:`~core2d.planner.known.KnownContour`):

1. C_A^B has meanwhile been traced through other areas -> closed as traced;
   so is a lid lying along contour recorded from B_i to A_i (a traced wall
   read backwards, :func:`~core2d.planner.along.reversed_lid`), and with a
   noisy sensor one lying along contour recorded from A_i towards B_i
   (:func:`~core2d.planner.along.on_recorded`). An end farther than eps from the
   recorded contour is joined to it by a W2 chord
   (:func:`~core2d.planner.mouths.traced_gaps`). With a noisy sensor a lid
   that repeats one closed ``open`` before, each end another reading of that
   lid's end, is closed ``open`` at once
   (:func:`~core2d.planner.repeats.repeats_opening`): its passes were made.
2. The lid could be a W3 lid only if it crosses no recorded contour
   (:func:`lid_like`). Then, if no straight line from F crosses the lid past the recorded
   contour farther than eps/2 from its touched ends (:func:`proof_lines`)
   -> **W3, proven**: the contour behind a lid is reachable only through
   the lid, and every line through it is blocked by real contour the robot
   has touched. This extends Area(G_i) = 0 (§4.2.1) from the posture held
   to every line through the lid.
3. Otherwise every free line is a pass the robot can try -- from V_i, or
   from the lid's other side when nothing reaches it from V_i (a chord
   between two corners that runs inside material, with the contour between
   them facing a gap) -- another pass, another side: it plays the role of Theorem 1's pass through
   L_{A0}^{B0} cap G_i cap V_i): the probe is inserted along it from F. A
   new contact C (farther than eps/2 from A_i and B_i and than 2 tol from
   everything recorded, and behind the lid or near it: :func:`in_reach`;
   with perfect sensing or a coarse noisy sensor a contact met in front of the lid whose
   children's lids would cross recorded contour is held back while a
   spread's worth more passes look for C_A^B:
   :func:`~core2d.planner.pass_contacts.splits_across_record`;
   with a noisy sensor the radii widen by the jitter, at most to the middle
   band eps/2 wide that a short lid keeps:
   :func:`~core2d.planner.short_lids.lid_end_radius`)
   splits the area into (A_i, C) and (C, B_i), which
   go back to the paper's flow. The first passes are spread over the lid
   and its free directions; then, if the lid could be W3, one pass every
   eps/2 along the lid, up to ``MAX_SWEEP`` (:mod:`core2d.planner.pass_plan`:
   each pass is planned when it is next, so a lid split early leaves the rest
   of its lid question unsolved). With a noisy sensor that resolves eps/2,
   once a pass has left through the lid, or ended anywhere but at a touched end
   (the lid can no longer be W3, step 5: the sweep then looks only for a new
   contact) the sweep goes on at one pass every eps, the paper's resolution
   (``sweep(sparse=)``): noise makes many lids over the gaps between islands
   and across slots whose walls are recorded in pieces, and each was swept at
   eps/2 (docs/notes/noise.md, "A lid that cannot be W3 swept at eps"). With a noisy
   sensor, :mod:`core2d.planner.grazing` leaves out the sweep passes too
   shallow to resolve eps/2, the passes through a spot where an earlier
   pass stopped in front of the lid (a spot off the lid is closed to its
   later lines, which then take their next widest gap:
   :meth:`~core2d.planner.lid_lines.FreeLines.block`), and contacts on the lid's line beyond
   its ends; and a pass that landed on the lid's line off its middle is
   made again along its line shifted sideways to land at the middle
   (:class:`~core2d.planner.reaim.Aim`, a noisy sensor whose jitter is
   at most 2 eps).
4. A lid that passed step 2 or the probing below is W3 only if the probe
   can hold it as a posture (:func:`~core2d.planner.w3_checks.holds_lid`: a W3 lid never passes
   through the solid; one it cannot hold gets swing passes under a coarse noisy sensor,
   :func:`~core2d.planner.swing_passes.swing_lid`; under a fine one, one more look
   whose lines ignore the readings within the jitter of the lid's line: a wall's own
   readings scattered into the slot in front of the lid hid it from every line) and if it closes
   a loop (:func:`~core2d.planner.w3_checks.closes_loop`): a chain of recorded pieces and such lids
   leads from B_i round to A_i, so A_i and B_i lie on one object and the lid
   bridges no islands (several hidden pockets of one loop close it
   together), and the loop encloses material (runs clockwise, at least
   :attr:`~core2d.resolution.Resolution.loop_width` thick, eps/4 with
   perfect sensing).
5. When no pass found anything new:

   * one left through the lid without any contact -> ``open``: the lid is
     an opening to F (a gap between separate objects, §3.2), nothing is
     written for the lid itself. That does not end the exploration of the
     contour behind its ends: A_i and B_i lie on two objects, and the
     contour that goes on round each object from A_i (C_{A_i} onward) and
     leads round to B_i faces away from the gap, where no pass through the
     lid reaches. The robot's map shows where: its recorded contour stops
     at A_i (a loose end) and begins again farther round (a loose start), and
     :func:`core2d.planner.audit.audit` registers the stretch between as an
     area of its own, which goes through the paper's flow like any
     A_iB_i. A stretch that stays untraced is reported unknown
     (:func:`core2d.planner.audit.report_leftovers`), never dropped;
   * the lid could be W3 and every pass, one per eps/2 along it, ended at one
     of its touched ends (within eps/2 of A_i or B_i) -> **W3 (step 4), probed at the
     paper's resolution**: the free lines left are those that graze the
     ends, as through a slit narrower than eps (Fig. 6(b)), and they touch
     nothing the resolution can tell from A_i or B_i. With a fine noisy
     sensor a pass counts only when it crosses the lid steeply enough to
     resolve eps/2 behind it (:func:`~core2d.planner.grazing.steep_enough`):
     a pass within a few degrees of the lid lands sigma / tan(alpha) from
     where it crossed, and such passes ending near A_i proved W3 a lid laid
     across a reachable slot 1.5 eps wide (``comb`` outline seed 1, sigma
     0.1 eps, sensor seed 1001: every pass ran within 6 degrees of the lid);
   * with a noisy sensor, the passes' contacts that were no new contact (on recorded
     contour, at an ancestor's split, near an end) but touched C_A^B at the lid -- the
     planned passes', then those aimed into the gaps between their touches
     (:class:`~core2d.planner.touched.Fill`), then, under a coarse sensor, swing passes
     into the gaps still open (:func:`~core2d.planner.swing_passes.swing_gaps`) --
     sample it finely enough -- no two
     neighbours along the lid, A_i and B_i included, as far
     apart as eps + jitter, the middle touched -> **W2** along their block means
     (:mod:`~core2d.planner.touched`): what the refused splits would have made;
   * otherwise -> ``unknown``, reported with the lid in the result -- with a noisy sensor
     whose passes touched the lid's middle, and W2 pieces where neighbouring touches lie
     nearer than eps + jitter.

A pass that touches reachable contour behind the lid farther than eps/2
from its ends -- the wall right behind a lid laid along it in a slot
narrower than eps -- finds a new contact, so such a lid is never W3.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from core2d.planner.along import on_recorded, reversed_lid
from core2d.planner.areas import Area
from core2d.planner.grazing import (Blockers, beyond_ends, end_radius, resolves_half_eps,
                                    steep_enough, sweep_length)
from core2d.planner.mouths import ALONG_RECORD, end_chords, record_gaps, traced_gaps
from core2d.planner.openings import soften_passed
from core2d.planner.pass_plan import MAX_SWEEP, MAX_TRIES, PassPlan, spread, sweep
from core2d.planner.reaim import Aim
from core2d.planner.repeats import repeats_opening
from core2d.planner.pass_contacts import in_reach, splits_across_record
from core2d.planner.short_lids import lid_end_radius, on_map
from core2d.planner.swing_passes import swing_gaps, swing_lid
from core2d.planner.touched import Fill, Touches, applies
from core2d.planner.w3_checks import closes_loop, holds_lid
from core2d.planner.tracing import reread_pass

if TYPE_CHECKING:  # the planner state that drives this module; typing only
    from core2d.planner.run import Exploration

__all__ = ["revisit", "finish", "lid_like", "proof_lines", "in_reach"]


def lid_like(run: Exploration, area) -> bool:
    """Step 2: the lid crosses no recorded contour."""
    return not run.known.crosses(area.a, area.b, run.res.tip_zone)


def proof_lines(run: Exploration, area, along: float = 0.0):
    """Free lines from F through the lid past the recorded contour, at lid
    samples farther than eps/2 from the touched ends: the W3 proof of step 2
    holds when there is none. ``along``: readings within it of the lid's
    line block nothing (:func:`revisit`)."""
    soften_passed(run)  # W2 chords the probe went through: openings (core2d.planner.openings)
    return run.known.free_lines(area.a, area.b, spacing=run.eps / 2,
                                margin=lid_end_radius(run.res, area.dist), min_gap=run.angle_tol,
                                along=along)


def _near_end(run: Exploration, area, point, radius=None) -> bool:
    """Within ``radius`` (default the same-contact radius, eps/2 + the
    sensor's jitter) of A_i or B_i: the same contact at the paper's
    resolution. The W3 of step 5 asks for the sensor's tolerance
    eps/2 + 2 noise instead (:attr:`~core2d.resolution.Resolution.sensor_tol`,
    eps/2 for perfect sensing): a pass ending farther is not read as a
    graze of an end, so noise never proves W3 (the area stays unknown)."""
    radius = run.res.tip_zone if radius is None else radius
    return min(np.hypot(*(point - area.a)), np.hypot(*(point - area.b))) <= radius


def _new_contact(run: Exploration, area, point, joint=None) -> bool:
    """Is ``point`` new: farther than eps/2 from A_i and B_i and from every
    contact an ancestor was split at by a pass
    (:func:`~core2d.planner.short_lids.lid_end_radius` with a noisy sensor),
    farther than 2 tol from the map (:func:`~core2d.planner.short_lids.on_map`),
    within the lid's reach (:func:`in_reach`, with a noisy sensor and
    the probe's ``joint`` given), and not making a child that repeats the A and B of
    an ancestor (§4.4)?"""
    same = lid_end_radius(run.res, area.dist)
    if _near_end(run, area, point, same) or run.known.distance(point) <= on_map(run.res, area.dist):
        return False
    if joint is not None and run.res.jitter > 0 and not in_reach(area, joint, point):
        run.orphans.note(run, point)  # far from the record: core2d.planner.orphans
        return False
    if beyond_ends(run.res, area.a, area.b, point):  # a grazing pass past an end
        return False
    if area.seen and np.hypot(*(np.asarray(area.seen) - point).T).min() <= same:
        return False
    for a, b in area.lineage:
        if (np.hypot(*(a - area.a)) <= same and np.hypot(*(b - point)) <= same) or (
                np.hypot(*(a - point)) <= same and np.hypot(*(b - area.b)) <= same):
            return False
    return True


def _split(run: Exploration, area, c, pose_c):
    """Split A_iB_i at the pass's contact C into (A_i, C) and (C, B_i)."""
    d, seen = area.depth + 1, area.seen + (c,)
    return run.children(area, [
        Area(area.a, c, area.pose_a, pose_c, area.index, "revisit", d, seen=seen),
        Area(c, area.b, pose_c, area.pose_b, area.index, "revisit", d, seen=seen)])


def revisit_one(run: Exploration, area, along: float = 0.0):
    """Look at one deferred area again (steps 1-3, 5 of the module doc).

    Returns a W3 reason when the lid passed its proof or its probing and
    waits for step 4, else None (the area was closed, split or deferred).
    ``along``: of :func:`proof_lines`."""
    probe, known = run.probe, run.known
    gaps = traced_gaps(known, area.a, area.b, run.res.tip_zone, run.res)
    if gaps is not None:
        return run.close(area, "traced", "C_A^B traced through other areas",
                         pieces={"W2": gaps} if gaps else None)
    for lies_on, note in zip((on_recorded, reversed_lid), ALONG_RECORD):
        if lies_on(run, area):  # the ends' chords and the record's breaks along the lid
            gaps = (end_chords(known, area.a, area.b, run.res)
                    + record_gaps(known, area.a, area.b, run.res))
            return run.close(area, "traced", note, pieces={"W2": gaps} if gaps else None)
    if repeats_opening(run, area):  # the same gap read again (core2d.planner.repeats)
        return run.close(area, "open", "the lid repeats an opening to F found before")
    candidate = lid_like(run, area)
    lines = proof_lines(run, area, along)
    if not lines and candidate:
        return "no line from F crosses the lid past the recorded contour"
    blocked = None  # the lines that blockers narrow (FreeLines.block)
    if lines:  # the spread passes, then (a W3 candidate) the sweep: each planned when next
        blocked = lines
        sources = [((p, d, None) for p, d in spread(lines, area.a, area.b,
                                                    distinct=run.res.jitter > 0))]
        if candidate:  # a noisy sensor: no grazing sweep passes (core2d.planner.grazing)
            sources.append((p, d, None) for p, d in sweep(
                lines, area.dist, sweep_length(run.res),
                sparse=lambda: (escaped or not ends_only) and resolves_half_eps(run.res))  # no W3
                           if steep_enough(run.res, area.a, area.b, d))
    else:  # nothing reaches the lid from V_i: try its other side
        back = run.known.free_lines(area.b, area.a, spacing=run.eps / 2,
                                    margin=run.res.tip_zone, min_gap=run.angle_tol)
        sources = [((p, d, None) for p, d in spread(back, area.b, area.a))] if back else []
    ends_only, escaped, held = True, False, None
    blockers = Blockers.of(run.res, 2.5 * probe.radius)  # passes stopped in front of the lid
    plan = PassPlan(sources)
    aim = Aim(run.res, np.asarray(area.a, float), np.asarray(area.b, float))
    touches = (Touches(run.res, aim.a, aim.b, lid_end_radius(run.res, area.dist))
               if lines and applies(run.res) else None)  # a noisy sensor's W2 by touch
    fill = (Fill(touches, aim, min(MAX_SWEEP, 2 * int(np.ceil(area.dist / run.res.w2_dist))),
                 lines)
            if touches is not None else None)  # then passes into the touches' gaps
    while (planned := plan.next()) is not None or (
            fill is not None and not escaped and (planned := fill.next()) is not None):
        if held and area.tries - held[2] >= MAX_TRIES:
            break  # a spread's worth of passes after it: it splits the lid (below)
        point, direction, shift = planned
        filling = plan.exhausted
        if not run.budget():
            return run.deferred.append(area)  # the budget ran out: still unknown
        if blockers.stops(point, direction):  # would meet contour a pass stopped at
            area.tries += 1
            ends_only = False
            continue
        probe.approach(point, direction)
        r = probe.insert(2.5 * probe.radius)
        c = r.tip_contact
        if c is not None:  # read again where the probe stands (reread_pass)
            c, pose_c = reread_pass(probe, r)
        if c is not None and _new_contact(run, area, c, pose_c.joint):
            if not splits_across_record(run.res, known, area, pose_c.joint, c):
                return _split(run, area, c, pose_c)
            held = held or (c, pose_c, area.tries + 1)  # split there if no later pass finds C_A^B
        area.tries += 1
        if c is not None and touches is not None:
            touches.add(pose_c.joint, c)
        escaped |= c is None
        ends_only &= (c is not None and _near_end(run, area, c, run.res.sensor_tol)
                      and steep_enough(run.res, area.a, area.b, direction))
        if c is not None and not _near_end(run, area, c) and blockers.add(
                area.a, area.b, pose_c.joint, c) and blocked is not None and blockers.off_lid(
                area.a, area.b, c):  # its disc closed to the lines after it
            blocked.block(c, blockers.radius)
        if filling:  # a pass into a gap: its landing steers the next
            if c is not None and shift is not None:
                aim.record(shift, c)
            continue
        again = None if c is None else aim.landed(point, direction, c, shift)
        if again is not None:  # a grazing pass landed off the middle: its line shifted
            plan.push(again)
    if held:  # no pass found C_A^B: the contact met in front splits the lid after all
        return _split(run, area, *held[:2])
    note = f"{area.tries} passes through the lid found nothing new"
    if not plan.count:
        return run.close(area, "unknown", "no line reaches the lid from either side, and it "
                                          "crosses recorded contour")
    if escaped:
        run.openings.append((area.a, area.b))
        return run.close(area, "open", note + "; one left through it: an opening to F")
    part = touches.pieces() if touches is not None else None
    if touches is not None and (part is None or "unknown" in part) and not (
            candidate and ends_only):  # a coarse sensor: swings into the touches' gaps
        part = swing_gaps(run, area, touches)
    if part is not None and "unknown" not in part:
        return run.close(area, "W2", note + "; they touched C_A^B along the lid, every "
                         "neighbour within eps + the sensor's jitter", pieces=part)
    if candidate and ends_only:
        return note + "; each ended at a touched end (resolution eps)"
    run.close(area, "unknown", note + ("; W2 where they touched C_A^B, neighbours within eps "
                                       "+ the sensor's jitter" if part else ""), pieces=part)


def revisit(run: Exploration) -> None:
    """Look at every deferred area of ``run`` again (see the module doc).

    Lids ready for W3 wait in ``run.waiting`` until they close a loop of the
    map together with all waiting lids (step 4); :func:`finish` reports
    those still waiting when nothing more can change."""
    todo, run.deferred = run.deferred, []
    for area in todo:
        run.probe.note_phase("revisit", area.index)
        why = revisit_one(run, area)
        if why is None:
            continue
        if holds_lid(run, area):
            run.waiting.append((area, why + "; the probe held the lid"))
        elif not swing_lid(run, area) and (  # fine: once more, past the wall's readings
                not resolves_half_eps(run.res)
                or revisit_one(run, area, run.res.jitter) is not None):
            run.close(area, "unknown", why + ", but the probe cannot hold the lid")
    if not run.waiting:
        return
    lids = [np.stack([a.a, a.b]) for a, _ in run.waiting]
    joint, first = run.known.with_pieces(lids), len(run.known.pieces)
    still = []
    for area, why in run.waiting:
        same_gap = [first + k for k, lid in enumerate(lids) if _same_gap(lid, area, run.eps)]
        if closes_loop(joint, area, run.res.tip_zone, run.res.loop_width, same_gap):
            run.close(area, "W3", why)
        else:
            still.append((area, why))
    run.waiting = still


def _same_gap(lid, area, eps) -> bool:
    """Does ``lid`` span the gap of ``area`` (its ends within eps of A_i and
    B_i, in either order)? Such a lid cannot close ``area``'s loop."""
    d = np.hypot(*(lid[:, None] - np.stack([area.a, area.b])[None]).transpose(2, 0, 1))
    return bool((d[0, 0] <= eps and d[1, 1] <= eps) or (d[0, 1] <= eps and d[1, 0] <= eps))


def finish(run: Exploration) -> None:
    """Report the lids still waiting for a loop as unknown."""
    for area, why in run.waiting:
        run.close(area, "unknown", why + ", but it closes no loop of recorded contour")
    run.waiting = []
