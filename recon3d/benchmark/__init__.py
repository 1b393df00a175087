"""``recon3d bench``: speed against accuracy, contact backends, the finger-probing
baseline and the stability study, as Dask tasks (:mod:`recon3d.benchmark.run3d`).

One module per part: :mod:`.pareto` (eps x slices, uniform and ``--slices
auto``), :mod:`.backends`, :mod:`.baseline`, :mod:`.stability`; :mod:`.cases`
the scenes and meshes they use; :mod:`.charts` the matplotlib pictures (kept
apart from the data; matplotlib comes through :mod:`recon3d.viz.libs`).
"""

PARTS = ("pareto", "backends", "baseline", "stability", "claims")
"""The parts of ``recon3d bench``, in the order they run (here, so that the command's
parser loads none of them)."""
