"""Scanned maps georeferenced by their own printed grid or graticule (issue 56): :mod:`.lines` finds
printed lines and where they cross, :mod:`.sheet` turns a few hints into every crossing of the sheet and
a model judged on crossings it was not fitted on.

Not yet a method a user can call (no front end reaches it): on synthetic sheets it finds every crossing
to under 0.3 px, but on the faint graticule of the development sheet ``scanned/nsw1907`` its verdict is
not yet reliable (``tests/core/test_grid.py`` holds what it does reach).
"""
