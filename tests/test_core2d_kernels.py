"""The compiled contact resolution (core2d.sim.kernels) against the Python path.

The kernels replace the Python searches of the simulator for a contact model
with a ray function (the Embree backend). They must resolve the same contacts
and count the same casts, casting the Python path's rays up to the first hit
of each window (the rest is never used): every test here runs the same scene
twice, once through the kernels and once through a wrapper that hides the ray
function (the Python path, ``cast`` and ``fan`` only), and compares everything
the run produces; the kernels' rays are fewer.
"""
import numpy as np
import pytest
from shapely.geometry import Polygon

import meshes
from core2d import sense_slice
from core2d.planner.tip_bound import polygon_rings, tip_bound
from core2d.sim import kernels
from core2d.sim.codes import WINDOWS
from core2d.sim.compiled import CompiledEngine
from core2d.sim.search import PythonEngine
from core2d.sim.probe import Probe
from slicer import slice_mesh
from slicer.contact.embree_direct import available

pytestmark = pytest.mark.skipif(not available(), reason="no Embree 4 library to call directly")


class _PythonPath:
    """The Embree contact model without its ray function."""

    def __init__(self, inner):
        self.inner, self.fan = inner, inner.fan

    def cast(self, origins, dirs, max_dist):
        return self.inner.cast(origins, dirs, max_dist)


def _geometry(res):
    return {k: [np.asarray(a).tolist() for a in getattr(res, k)]
            for k in ("w1", "w2", "w3", "unknown")}


def _cut(name, index, count):
    mesh = meshes.load(name)
    eps = float(np.linalg.norm(np.ptp(mesh.bounds, axis=0)) / 200)
    cut = slice_mesh(mesh, axis="z", count=count)[index]
    center, radius = cut.bounding_circle()
    return cut.contact("embree"), (center, radius + eps), eps


@pytest.mark.parametrize("name,index", [("fig17_pocket", 0), ("fig18_overhangs", 1),
                                        ("twin_posts", 1), ("mushroom", 2)])
def test_kernels_sense_exactly_as_the_python_path(name, index):
    contact, ws, eps = _cut(name, index, 4)
    assert contact.ray_kernel is not None
    assert type(Probe(contact, ws, eps).engine) is CompiledEngine
    assert type(Probe(_PythonPath(contact), ws, eps).engine) is PythonEngine
    fast = sense_slice(contact, ws, eps)
    slow = sense_slice(_PythonPath(contact), ws, eps)
    assert _geometry(fast) == _geometry(slow)
    for key in ("motions", "casts", "pushes", "push_attempts", "joint_path"):
        assert getattr(fast.stats, key) == getattr(slow.stats, key), key
    assert fast.stats.motions > 100 and fast.stats.rays > 10_000
    assert fast.stats.rays < 0.9 * slow.stats.rays  # windows stop at their first hit
    _same_log(fast.motions, slow.motions)  # the motion log records both engines alike


def _same_log(a, b):
    assert len(a) == len(b) > 0
    for key in ("kind", "phase", "area", "event", "contacts", "other_start", "blocked",
                "torque"):
        assert np.array_equal(getattr(a, key), getattr(b, key)), key
    for key in ("before", "after", "tip", "tip_contact", "other"):
        np.testing.assert_allclose(getattr(a, key), getattr(b, key), atol=1e-9, err_msg=key)


def test_kernel_windows_are_the_probe_offsets():
    contact, ws, eps = _cut("fig18_overhangs", 1, 4)
    probe = Probe(_PythonPath(contact), ws, eps)
    cap = WINDOWS[-1]
    offs, st = np.empty(cap), np.zeros(4)
    for max_angle in (0.0, probe.fan_step / 3, 0.01, 1.0, 3.5, 7.0):
        st[:] = (0.0, 0.0, min(probe.fan_step, 2 * probe.ang_tol), 0.0)
        got = []
        while n := kernels._window(offs, st, max_angle, probe.fan_step, cap):
            got.append(offs[:n].copy())
        want = list(probe.engine._offsets(max_angle))
        assert len(got) == len(want)
        assert all(np.array_equal(g, w) for g, w in zip(got, want))


def _tip_bound_reference(probe, G, a, b, theta, rot_dir, limit):
    """Theorem 3 on the whole arc with shapely and numpy (the former path)."""
    import shapely

    n = max(4, int(limit / probe.resolution.fan_angle(probe.length)))
    k = np.arange(1, n + 1)
    angs = theta + rot_dir * limit * k / n
    tips = probe.joint + probe.length * np.stack([np.cos(angs), np.sin(angs)], 1)
    cross = lambda x, y: x[..., 0] * y[..., 1] - x[..., 1] * y[..., 0]  # noqa: E731
    free = cross(a - tips, b - tips) > 0
    inside = shapely.contains_xy(G, tips[:, 0], tips[:, 1])
    ab, pt = b - a, tips - probe.joint
    lid = (cross(ab, probe.joint - a) * cross(ab, tips - a) < 0) & (
        cross(pt, a - probe.joint) * cross(pt, b - probe.joint) < 0)
    bad = ~((free & inside) | (~free & lid))
    return float(limit * int(np.argmax(bad)) / n) if bad.any() else limit


def test_tip_bound_matches_shapely_on_random_regions():
    contact, ws, eps = _cut("fig17_pocket", 0, 1)
    probe = Probe(_PythonPath(contact), ws, eps)
    rng = np.random.default_rng(7)
    cut_short = 0
    for _ in range(200):
        a, b = rng.normal(size=(2, 2)) * probe.radius
        joint = probe.joint = (a + b) / 2 + rng.normal(size=2) * probe.length
        G = Polygon([joint, a, b, joint + rng.normal(size=2) * probe.radius]).buffer(probe.tol)
        if not G.is_valid or G.is_empty:
            continue
        theta = float(np.arctan2(*((a + b) / 2 - joint)[::-1]))
        for rot in (1, -1):
            limit = float(rng.uniform(0.0, 0.5))
            want = _tip_bound_reference(probe, G, a, b, theta, rot, limit)
            got = tip_bound(probe, polygon_rings(G), a, b, theta, rot, limit)
            assert got == want
            cut_short += got < limit
    assert cut_short > 50  # the bound is not trivially the limit


def _extruded_contact(loops):
    """The Embree contact of a block loop extruded along z, cut at z = 1 in
    the loop's own (x, y) frame."""
    import trimesh
    from shapely.geometry import Polygon as ShapelyPolygon

    from slicer.contact.embree import EmbreeContact
    from slicer.planes import SlicePlane

    mesh = trimesh.creation.extrude_polygon(ShapelyPolygon(loops[0]), height=2.0)
    z = np.array([0.0, 0.0, 1.0])
    plane = SlicePlane(0, z.copy(), z.copy(), np.array([1.0, 0.0, 0.0]),
                       np.array([0.0, 1.0, 0.0]), 1.0)
    return EmbreeContact(mesh, plane)


def trace_constructed(model, at, direction, a, b, toward_b=True, length=None,
                      pose_b=(0.0, -1.0)):
    """One trace of the planner on a constructed slice (eps = 1): the probe placed touching
    ``at`` along ``direction``, the area from A = ``a`` to B = ``b`` (A's posture pointing
    down, B's along ``pose_b``), traced towards B or A (:func:`trace_side`, Theorem 4's
    local result from the placed reading). Returns ``(probe, lines, new areas, cases)``."""
    from figure_scenes import WORKSPACE, place, pose_to

    from core2d.planner.areas import Area
    from core2d.planner.local_search import LocalResult, definition5
    from core2d.planner.regions import G_region
    from core2d.planner.tracing import trace_side

    probe = Probe(model, WORKSPACE, 1.0, length=length)
    r = place(probe, at, np.asarray(direction, float) / np.linalg.norm(direction))
    area = Area(np.asarray(a, float), np.asarray(b, float),
                pose_to(probe, a, np.array([0.0, -1.0])), pose_to(probe, b, np.asarray(pose_b)))
    local = LocalResult(r, r.tip_contact.point, *definition5(r), 0)
    G = G_region(area.a, area.b, area.pose_a, area.pose_b)
    lines, new, cases, _ = trace_side(probe, area, G, r.joint.copy(), local, toward_b,
                                      lambda: True)
    return probe, lines, new, cases


# The constructed trace events of tests/test_core2d_cases.py, each met on purpose.
_EVENTS = {
    "case2-3": ([(0, 60), (100, 60)], (50, 60), (-1, -1), (10, 60), (100, 30), None, True,
                dict(pose_b=(-1, 0))),
    "case3": ([(0, 30), (50, 30), (50, 70), (100, 70)], (45, 75), (-0.5, -np.sqrt(3) / 2),
              (5, 30), (95, 70), 20, True, {}),
    "case4": ([(0, 60), (40, 60), (40, 30), (70, 30), (70, 45), (55, 45), (55, 55), (100, 55)],
              (45, 75), (np.sin(np.radians(60)), -np.cos(np.radians(60))), (5, 60), (95, 55),
              20, False, {}),
    "left": ([(0, 60), (30, 60), (40, 30), (70, 60), (100, 60)], (40, 60), (0, -1), (70, 60),
             (30, 60), None, True, {}),
}


@pytest.mark.parametrize("case", sorted(_EVENTS))
def test_kernels_meet_each_trace_event_as_the_python_path(case):
    """Every event of the compiled micro-step loop (lost contact, the Case 3
    guard, Case 4, the trace passing the other end) on a constructed slice
    through the Embree backend: the compiled and the Python path record the
    same event, trace, new areas and counters."""
    from figure_scenes import block

    top, at, direction, a, b, length, toward_b, kw = _EVENTS[case]
    contact = _extruded_contact(block(top))
    assert contact.ray_kernel is not None
    got = []
    for model in (contact, _PythonPath(contact)):
        probe, lines, new, cases = trace_constructed(model, at, direction, a, b, toward_b,
                                                     length, kw.get("pose_b", (0.0, -1.0)))
        got.append((cases, [np.asarray(pl).tolist() for pl in lines],
                    [(k.rule, k.a.tolist(), k.b.tolist()) for k in new],
                    probe.joint.tolist(), float(probe.theta),
                    {k: getattr(probe.stats, k) for k in ("motions", "casts",
                                                          "push_attempts", "joint_path")},
                    probe.stats.rays))
    assert case in got[0][0]  # the event under test is met
    assert got[0][:-1] == got[1][:-1]
    assert got[0][-1] < got[1][-1]  # fewer rays: the windows stop at their first hit


class _Wall:
    """A synthetic scene: a ray from the joint is blocked (at distance 1) when
    its direction angle is at least ``phi``. It serves both engines: a
    batched ``cast`` for the Python one, a C ray function (ctypes) for the
    kernels; both log the angle of every ray, cast by cast."""

    def __init__(self, phi):
        import ctypes

        self.phi, self.casts, self.log = phi, [], []
        proto = ctypes.CFUNCTYPE(None, ctypes.c_void_p, *[ctypes.c_double] * 5,
                                 ctypes.POINTER(ctypes.c_double))

        def ray(ctx, ox, oy, dx, dy, max_dist, out):
            a = float(np.arctan2(dy, dx))
            self.log.append(a)
            hit = a >= self.phi
            out[0], out[1], out[2] = (1.0, ox + dx, oy + dy) if hit else (np.inf, np.nan, np.nan)

        self._fn = proto(ray)  # kept alive with this object
        self.ray_kernel = (ctypes.cast(self._fn, ctypes.c_void_p).value, np.zeros(1))

    def cast(self, origins, dirs, max_dist):
        a = np.arctan2(dirs[:, 1], dirs[:, 0])
        self.casts.append(a)
        hit = a >= self.phi
        return (np.where(hit, 1.0, np.inf), np.where(hit[:, None], origins + dirs, np.nan),
                None)


@pytest.mark.parametrize("want_blocked", [True, False])
def test_search_windows_stop_at_their_first_hit(want_blocked):
    """The compiled search casts each of the Python search's fans (windows,
    then the bisection's fans) up to its first ray where the state changes,
    and nothing else: same answer, same casts, ray by ray the prefixes."""
    from core2d.resolution import Resolution
    from core2d.result import SenseStats

    res, length = Resolution.of(0.05), 1.0
    rot = 1 if want_blocked else -1  # from free towards the wall, or from inside it out
    theta0 = 0.0 if want_blocked else 1.0
    wall = _Wall(0.437)
    slow = PythonEngine(wall, SenseStats(), length, res).search(
        np.zeros(2), theta0, rot, 2.0, want_blocked)
    fast_engine = CompiledEngine(wall, SenseStats(), length, res, wall.ray_kernel)
    fast = fast_engine.search(np.zeros(2), theta0, rot, 2.0, want_blocked)
    assert slow is not None and fast[0] == slow[0]
    np.testing.assert_array_equal(fast[1][1], slow[1][1])
    want = []
    for fan in wall.casts:
        state = fan >= wall.phi if want_blocked else fan < wall.phi
        k = int(np.argmax(state)) + 1 if state.any() else len(fan)
        want.extend(fan[:k])
    assert len(wall.casts) > 3 and fast_engine.stats.casts == len(wall.casts)
    assert fast_engine.stats.rays == len(wall.log) == len(want)
    assert len(want) < sum(map(len, wall.casts))  # some fan was cut short
    np.testing.assert_allclose(wall.log, want, rtol=0, atol=1e-12)
