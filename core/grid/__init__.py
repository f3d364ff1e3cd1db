"""Scanned maps georeferenced by their own printed grid or graticule (issue 56), from the coordinates printed
in the sheet's margins, or from two or three crossings placed roughly with their coordinates (hints, a QGIS
Georeferencer ``.points`` file):

- :mod:`.labels` reads the printed coordinates (Tesseract) and makes hints of them;
- :mod:`.scan` reads the scan's line map window by window (a 30 000 px scan is never held whole);
- :mod:`.lattice` places every grid line of the sheet at once on it, from the hints' first model;
- :mod:`.lines` finds where two printed lines cross, to a fraction of a pixel;
- :mod:`.sheet` turns the lattice into every crossing of the sheet, each checked against its grid line;
- :mod:`.register` makes a registration result of them (GCPs onto a frame in the sheet's CRS, the model
  chosen by the check, the check itself: each grid line predicted by the model fitted without it).
"""
