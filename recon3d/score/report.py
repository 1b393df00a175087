"""The headline of a scored run as text: what the summary prints and coverage.png shows.

Every number says what it is measured over: F@1% over the scored ground
truth (the slab, as a share of the whole ground truth), over its
reachable part and, where openings narrower than eps hold part of that, over
the part eps resolves; with several families, each family's own surface over its
own slab and the fused surface against the best of them. Numbers go through
:func:`recon3d.spellings.number` (no negative zero).
"""
from __future__ import annotations

from recon3d.score.unknowns import CAUSES
from recon3d.spellings import number, percent

__all__ = ["surface_lines", "chord_lines", "slicing_text", "NARROW"]

NARROW = 0.001
"""Share of the ground truth inside openings narrower than eps from which the summary also
gives F@1% over the part eps resolves (:mod:`core2d.truth.resolvable`)."""


def _f1(block) -> str:
    return number(((block or {}).get("fscore") or {}).get("1%"))


def _scored(entry: dict, surface: dict | None, what: str) -> str:
    """``F@1% a over <what> (s% of the ground truth), r over its reachable part (q%)``, and
    where openings narrower than eps take part of that (:data:`NARROW` of the ground
    truth or more), ``, v over the part eps resolves (w%)``.

    >>> e = {"slab_share": 0.8, "reachable_share": 0.7, "resolvable_share": 0.6}
    >>> s = {"fscore": {"1%": 0.8}, "reachable": {"fscore": {"1%": 0.85}},
    ...      "resolvable": {"fscore": {"1%": 0.97}}}
    >>> _scored(e, s, "the slab")  # doctest: +NORMALIZE_WHITESPACE
    'F@1% 0.800 over the slab (80% of the ground truth), 0.850 over its reachable part
     (70% of the ground truth), 0.970 over the part eps resolves (60%: openings narrower
     than eps left out)'
    >>> _scored({**e, "resolvable_share": 0.6995}, s, "the slab").endswith("(70% of the ground truth)")
    True
    """
    out = (f"F@1% {_f1(surface)} over {what} ({percent(entry.get('slab_share'))} of the "
           f"ground truth), {_f1((surface or {}).get('reachable'))} over its reachable part "
           f"({percent(entry.get('reachable_share'))} of the ground truth)")
    reach, resolved = entry.get("reachable_share"), entry.get("resolvable_share")
    if reach is not None and resolved is not None and reach - resolved >= NARROW:
        out += (f", {_f1((surface or {}).get('resolvable'))} over the part eps resolves "
                f"({percent(resolved)}: openings narrower than eps left out)")
    return out


def slicing_text(metrics: dict) -> str:
    """``z x16 + x x16``: the families as sliced (axis and slice count)."""
    return " + ".join(f"{f['axis']} x{f['slices']}" for f in metrics.get("families", []))


def surface_lines(metrics: dict) -> list[str]:
    """The 3D headline of a metrics.json document, one line per scored surface.

    >>> doc = {"families": [{"axis": "z", "slices": 8}], "total": {"surface": None},
    ...        "surface_eval": {"notes": []}}
    >>> surface_lines(doc)
    ['no surface: nothing sensed']
    """
    ev, surf = metrics.get("surface_eval", {}), metrics["total"].get("surface")
    if surf is None:
        return ["no surface: " + ("; ".join(ev.get("notes", [])) or "nothing sensed")]
    fams = ev.get("families", [])
    name = "fused " + "+".join(f["axis"] for f in fams) if len(fams) > 1 else "surface"
    lines = [f"{name}: {_scored(ev, surf, 'the slab')}"]
    if len(fams) > 1:
        for fam in fams:
            lines.append(f"{fam['axis']} alone: {_scored(fam, fam.get('surface'), 'its slab')}")
        vs = ev.get("fused_vs_best")
        if vs is not None:
            d = vs["fscore_1%"]  # 4 decimals where 3 would print a nonzero gap as +0.000
            fmt = "+.4f" if d is not None and 0 < abs(d) < 5e-4 else "+.3f"
            lines.append(f"fused against the best single axis ({vs['axis']} alone): F@1% "
                         f"{number(d, fmt)}")
    return lines


def chord_lines(metrics: dict, shown: int = 4) -> list[str]:
    """The unknown chords of a metrics.json document: count, cause, where (``axis#k``)."""
    chords = metrics.get("unknown_chords") or []
    if not chords:
        return []
    total = sum(c["length"] for c in chords)
    budget, loose = (sum(c["cause"] == k for c in chords) for k in ("budget", "loose end"))
    dead = len(chords) - budget - loose
    lines = [f"{len(chords)} unknown chord{'s' if len(chords) > 1 else ''} (total length "
             f"{number(total, '.3g')}): {budget} from a budget hit, {dead} "
             f"dead end{'' if dead == 1 else 's'} ({CAUSES['dead end']})"
             + (f", {loose} loose end{'' if loose == 1 else 's'} ({CAUSES['loose end']})"
                if loose else "")]
    for c in chords[:shown]:
        mid = ", ".join(number(v, ".4g") for v in c["middle"])
        lines.append(f"  {c['axis']}#{c['slice']} at ({mid}), length {number(c['length'], '.3g')}, "
                     f"on the contour {percent(c['on_contour'])}: {c['note']}")
    if len(chords) > shown:
        lines.append(f"  and {len(chords) - shown} more (metrics.json: unknown_chords)")
    return lines
