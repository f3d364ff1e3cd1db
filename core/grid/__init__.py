"""Scanned maps georeferenced by their own printed grid or graticule, from the coordinates printed in the sheet's
margins, or from two or three crossings placed roughly with their coordinates (hints, a QGIS Georeferencer
``.points`` file):

- :mod:`.ocr` finds the words in the margins and reads them (Tesseract, RapidOCR); :mod:`.labels` parses each;
  :mod:`.reading` makes hints of the labels that agree (:mod:`.edges` fits each edge's labels);
- :mod:`.scan` reads the scan's line map window by window (a 30 000 px scan is never held whole);
- :mod:`.steps` the grid's usual steps, :mod:`.planes` the planes a graticule may be drawn in;
- :mod:`.placing` places the lattice of every grid line at once from the hints' first model (:mod:`.lattice`
  fits it), and :mod:`.evidence` judges whether it is printed against the sheet's own background; :mod:`.frame`
  finds the neatline and its ticks;
- :mod:`.sheet` searches the steps and planes; :mod:`.finding` finds every crossing where it is printed
  (:mod:`.lines`: two printed lines' crossing, to a fraction of a pixel);
- :mod:`.check` chooses the model and the verdict (each grid line predicted by the model fitted without it;
  the labels of opposite edges against the lattice), once; :mod:`.register` makes a registration result of it.
"""
