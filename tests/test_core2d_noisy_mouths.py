"""Mouths a fine noisy sensor cannot tell from eps: :mod:`core2d.planner.mouths`.

A thin wall 2 eps thick beside a block, the slit between them 1.26 eps wide,
40 eps long and open at both ends (the outer wall of the shared mesh
``trimesh_octagonal_pocket`` and its body, slices z0, z1, z6, z7). At sigma
0.1 eps its mouths read about 1 - 1.4 eps across, below the W2 distance eps +
jitter (1.42 eps), and the map joins the wall's end to the block's corner
across them: without the two rules every mouth was W2 at once or "traced
through other areas", and the slit's walls were never touched.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from core2d.planner.areas import Area
from core2d.planner.known import KnownContour
from core2d.planner.mouths import covered, is_mouth
from core2d.planner.run import Budget, Exploration
from core2d.resolution import Resolution
from noisy_runs import coverages

WALL = np.array([[-3.26, -20.0], [-1.26, -20.0], [-1.26, 20.0], [-3.26, 20.0]])
BLOCK = np.array([[0.0, -20.0], [14.0, -20.0], [14.0, 20.0], [0.0, 20.0]])
WORKSPACE = (np.array([5.4, 0.0]), 27.0)
FINE, COARSE = Resolution.of(1.0, noise=0.1), Resolution.of(1.0, noise=0.3, taxel=0.25)


@pytest.mark.parametrize("dist, rule, mouth", [
    (0.99, "case2-1", False), (1.0, "case2-1", True), (1.26, "case2-2", True),
    (1.26, "hop", True), (1.42, "case2-1", True), (1.43, "case2-1", False),
    (1.26, "escape", False), (1.26, "revisit", False), (1.26, "one-sided", False)])
def test_a_mouth_is_a_jump_reading_between_eps_and_eps_plus_jitter(dist, rule, mouth):
    assert is_mouth(FINE, dist, rule) is mouth  # jitter 0.424
    assert not is_mouth(Resolution.of(1.0), dist, rule)  # perfect sensing: no mouth
    assert not is_mouth(COARSE, dist, rule)  # readings that do not resolve eps/2


@pytest.mark.parametrize("gap, fine", [(1.2, False), (0.8, True)])
def test_a_chain_that_hops_a_mouth_covers_nothing(gap, fine):
    """Two collinear pieces (a wall's end face and a block's, across the slit's
    mouth): the map joins them (join = w2_dist = 1.42), but a hop of eps or
    more is an opening, not traced contour."""
    known = KnownContour(join=FINE.w2_dist)
    known.add([[0.0, 0.0], [4.0, 0.0]])
    known.add([[4.0 + gap, 0.0], [9.0, 0.0]])
    assert known.covers([1.0, 0.0], [8.0, 0.0], 0.1)
    assert known.widest_hop([1.0, 0.0], [8.0, 0.0], 0.1) == pytest.approx(gap)
    assert covered(known, [1.0, 0.0], [8.0, 0.0], 0.1, FINE) is fine
    assert covered(known, [1.0, 0.0], [8.0, 0.0], 0.1, COARSE)  # sigma 0.3: covers


def test_the_slit_beside_a_thin_wall_at_sigma_01_eps():
    covs = coverages([WALL, BLOCK], WORKSPACE, 0.1, range(6))
    # 0.985 with both rules; 0.77 without the mouths, 0.66 without the hop rule
    assert covs.mean() >= 0.97, covs


@pytest.mark.parametrize("mouth, outcome", [(True, "W2"), (False, "deferred")])
def test_a_mouth_at_a_dead_end_is_w2(mouth, outcome):
    """A mouth whose processing found nothing is closed W2, as it was before
    it was processed; any other dead end waits for the revisit."""
    probe = SimpleNamespace(resolution=FINE, length=20.0, motions=7)
    run = Exploration(probe, 1.0, Budget(probe))
    area = Area(np.array([0.0, 0.0]), np.array([1.2, 0.0]), None, None, rule="case2-1",
                mouth=mouth)
    run.add(area)
    run.defer(area, "Theorem 1 pass found no new contact")
    assert run.result.areas[area.index].outcome == outcome
    assert len(run.result.w2) == mouth and (run.deferred == []) == mouth
