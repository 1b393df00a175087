"""Replaying motions.csv: the recorded joint poses give back the recorded contacts.

``recon3d run`` writes motions.csv; for every row, the simulator is set to
the row's joint position and angle after the motion and its sensors are read
(:meth:`core2d.sim.probe.Probe.sense`, no motion). The tip contact flag, the
number of contacts and the torque sensor's blocked rotations must come back
exactly; contact points within the tip zone (eps/2, one contact at the
paper's resolution): a motion that stops on a contact reports the contact
its own search found (the swing's fan, the trace's settle), the replay the
one of the sensor's rays at that pose -- the same contact, a little along the
surface. Insertions stop on the tip's own ray: those points come back within
the contact resolution tol.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import meshes
import slicer
from core2d.sim.probe import Probe
from recon3d.cli import main
from recon3d.io.motions import other_points, read_motions
from recon3d.sensing.worker import family_slices


@pytest.mark.parametrize("scene", ["fig17_pocket", "fig18_overhangs"])
def test_replaying_the_joint_poses_gives_back_the_contacts(scene, tmp_path):
    out = tmp_path / scene
    assert main(["run", scene, "--slices", "2", "--no-png", "--quiet", "--out", str(out)]) == 0
    doc = json.loads((out / "sensing.json").read_text())
    eps, tol = doc["eps"], doc["tol"]
    zone = eps / 2
    m = read_motions(out)
    assert len(m) == sum(s["stats"]["motions"] for s in doc["slices"])
    cuts = family_slices(meshes.load(scene), slicer.parse_axis("z"), 2)
    for s in doc["slices"]:
        cut = cuts[s["index"]]
        center, radius = cut.bounding_circle()
        probe = Probe(cut.contact("embree"), (np.asarray(center, float), float(radius) + eps),
                      eps, tol=tol)
        rows = m[(m["family"] == s["family"]) & (m["slice"] == s["index"])]
        assert len(rows) == s["stats"]["motions"] > 100
        L = np.hypot(rows["tip_x1"] - rows["joint_x1"], rows["tip_y1"] - rows["joint_y1"])
        np.testing.assert_allclose(L, probe.length, rtol=1e-9)
        for row in rows:
            probe.joint = np.array([row["joint_x1"], row["joint_y1"]])
            probe.theta = float(row["theta1"])
            r = probe.sense()
            tip = r.tip_contact
            assert (tip is not None) == bool(row["tip_contact"]), row
            assert len(r.contacts) == row["contacts"], row
            assert (r.blocked_ccw, r.blocked_cw) == (bool(row["blocked_ccw"]),
                                                     bool(row["blocked_cw"])), row
            if tip is not None:
                d = np.hypot(tip.point[0] - row["tip_cx"], tip.point[1] - row["tip_cy"])
                assert d <= (tol if row["kind"] == "insert" else zone), row
            others = np.array([c.point for c in r.contacts if c is not tip]).reshape(-1, 2)
            for p in other_points(row["other_contacts"]):
                assert np.hypot(*(others - p).T).min() <= zone, row
