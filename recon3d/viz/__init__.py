"""Pictures: the ``scene.vtm`` blocks (:mod:`.blocks`) and the pyvista coverage panels
(:mod:`.plot`), drawn from plain data; :mod:`.libs` loads pyvista and matplotlib lazily.

Importing this package loads neither pyvista nor matplotlib.
"""
