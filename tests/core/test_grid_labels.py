"""The printed labels as the engine reads them: what each word says (:mod:`hamta.core.grid.labels`) and what a
sheet's words say together (:func:`hamta.core.grid.reading.interpret`), on words placed by hand."""
import pytest
from pyproj import CRS

from hamta.core.grid.labels import joined, normalised, parse
from hamta.core.grid.reading import interpret
from hamta.core.grid.words import Word


def word(text, x=100.0, y=10.0, glyph=12.0, confidence=90.0):
    return Word(text, (x - 2 * glyph, y - glyph / 2, x + 2 * glyph, y + glyph / 2), 0, glyph, confidence)


@pytest.mark.parametrize("text, degrees, minutes, seconds, hemisphere", [
    ("48°07'", 48, 7.0, None, ""),
    ("N 44°27'", 44, 27.0, None, "N"),
    ("156°59'30\"W", 156, 59.0, 30.0, "W"),
    ("45N", 45, None, None, "N"),
    ("W95", 95, None, None, "W"),
    ("59.5'", None, 59.5, None, ""),
    ("07'", None, 7.0, None, ""),
    ("15\"", None, None, 15.0, ""),
    ("06° 08'", 6, 8.0, None, ""),
    ("50o51'", 50, 51.0, None, ""),  # a degree sign read as the letter o
    ("48°07\"", 48, 7.0, None, ""),  # a prime read as a double prime after degrees: minutes
    ("048°", 48, None, None, ""),  # zero-padded
])
def test_angles_are_parsed_with_their_parts_and_hemisphere(text, degrees, minutes, seconds, hemisphere):
    lab = parse(word(text), "top")
    assert lab is not None and lab.angle and lab.marked
    assert (lab.degrees, lab.minutes, lab.seconds, lab.hemisphere) == (degrees, minutes, seconds, hemisphere)


@pytest.mark.parametrize("text, number, whole", [
    ("503000", 503000.0, True), ("5 540 000", 5540000.0, True), ("5,540,000", 5540000.0, True),
    ("85", 85.0, False), ("10000", 10000.0, True), ("0600", 600.0, False)])
def test_numbers_are_a_grids_values_in_full_or_abbreviated(text, number, whole):
    lab = parse(word(text), "left")
    assert lab is not None and not lab.angle and lab.number == number and lab.whole is whole


@pytest.mark.parametrize("text", ["SCALE", "N44N", "12a", "4°5°", "61'", "200°", "1.5", "", "12-3", "E12E"])
def test_words_that_are_no_coordinate_are_not_labels(text):
    assert parse(word(text), "top") is None


def test_look_alikes_are_folded():
    assert normalised("44’30′") == "44'30'"
    assert normalised(" 5 540 000, ") == "5540000"


def test_the_parts_of_one_label_printed_apart_are_joined():
    size = 12.0
    degrees, minutes = parse(word("91°", 100, 20, size), "top"), parse(word("48'", 140, 21, size), "top")
    (one,) = joined([degrees, minutes])
    assert (one.degrees, one.minutes) == (91, 48.0)
    below = parse(word("20°", 400, 20, size), "left"), parse(word("47'", 402, 34, size), "left")
    (two,) = joined(list(below))
    assert (two.degrees, two.minutes) == (20, 47.0)
    thousands = parse(word("1742", 600, 20, size), "top"), parse(word("500", 640, 20, size), "top")
    (three,) = joined(list(thousands))
    assert three.number == 1742500.0
    far = parse(word("91°", 100, 20, size), "top"), parse(word("48'", 400, 20, size), "top")
    assert len(joined(list(far))) == 2  # too far apart to be one label
    sides = parse(word("91°", 100, 20, size), "top"), parse(word("48'", 140, 21, size), "left")
    assert len(joined(list(sides))) == 2  # read along different edges
    scale = [parse(word(t, x, 20, size), "top") for t, x in (("1:", 600), ("100", 625), ("000", 665))]
    assert sorted(lab.number for lab in joined(scale)) == [1.0, 100000.0]  # "1:" is no thousands of a number


def labelled_sheet(width=1200, height=900, x0=150.0, px_per_minute=150.0, misread=None):
    """Minutes of a graticule every 1', labelled on the four edges as a chart prints them: the degrees with the
    first label of each edge, minutes alone between; lines at x0 + k * px_per_minute (longitude 70°10'W + k') and
    y = x0 + k * px (latitude 42°20'N - k'). ``misread`` (text, by) replaces one label's text."""
    labels = []
    for k in range(7):
        x = x0 + k * px_per_minute
        if x > width - 50:
            break
        minutes = 10 - k  # west: longitude grows westward to the left
        text = f"70°{minutes:02d}'W" if k == 0 else f"{minutes:02d}'"
        for side, y in (("top", 20.0), ("bottom", height - 20.0)):
            labels.append(parse(word(text, x, y), side))
    for k in range(5):
        y = x0 + k * px_per_minute
        if y > height - 50:
            break
        text = f"42°{20 - k:02d}'N" if k == 0 else f"{20 - k:02d}'"
        for side, x in (("left", 30.0), ("right", width - 30.0)):
            labels.append(parse(word(text, x, y), side))
    if misread is not None:
        i, text = misread
        old = labels[i]
        labels[i] = parse(word(text, *old.xy), old.side)
    return labels, width, height


def test_a_labelled_graticule_gives_its_crossings_and_its_step():
    labels, w, h = labelled_sheet()
    reading = interpret(labels, w, h, CRS.from_epsg(4326))
    assert reading.hints is not None, reading.reason
    assert reading.printed_crs.is_geographic
    assert reading.steps is not None and min(abs(s - 1 / 60) for s in reading.steps[0]) < 1e-9
    for x, y, lon, lat in reading.hints:  # each crossing where the construction put it
        k, j = (x - 150.0) / 150.0, (y - 150.0) / 150.0
        assert lon == pytest.approx(-(70 + (10 - k) / 60), abs=1e-6)
        assert lat == pytest.approx(42 + (20 - j) / 60, abs=1e-6)
    assert sum(f.startswith("kept") for f in reading.fates) >= 16


def test_a_label_misread_by_a_whole_step_is_not_kept():
    labels, w, h = labelled_sheet(misread=(4, "07'"))  # the third top label says 07' where 08' is printed
    reading = interpret(labels, w, h, CRS.from_epsg(4326))
    assert reading.hints is not None, reading.reason
    assert not reading.fates[4].startswith("kept")
    for x, y, lon, lat in reading.hints:
        assert lon == pytest.approx(-(70 + (10 - (x - 150.0) / 150.0) / 60), abs=1e-6)


def test_labels_of_one_edge_alone_are_no_crossings_and_it_says_why():
    labels, w, h = labelled_sheet()
    top = [lab for lab in labels if lab.side == "top"]
    reading = interpret(top, w, h, CRS.from_epsg(4326))
    assert reading.hints is None and "latitude" in reading.reason and "hints" in reading.reason


def test_a_grids_numbers_given_a_crs_in_degrees_are_refused_with_the_reason():
    labels = [parse(word(f"{500000 + 1000 * k}", 150 + 150 * k, 20), "top") for k in range(5)]
    labels += [parse(word(f"{5540000 - 1000 * k}", 30, 150 + 150 * k), "left") for k in range(4)]
    reading = interpret(labels, 1000, 800, CRS.from_epsg(4326))
    assert reading.hints is None and "projected grid" in reading.reason


def test_a_grids_numbers_in_full_and_abbreviated_give_its_crossings():
    labels = []
    for k in range(5):
        text = f"{500 + k}000" if k == 0 else f"{(500 + k) % 100:02d}"
        labels += [parse(word(text, 150 + 150 * k, 20), "top"), parse(word(text, 150 + 150 * k, 780), "bottom")]
    for k in range(4):
        text = f"{5540 - k}000" if k == 0 else f"{(5540 - k) % 100:02d}"
        labels += [parse(word(text, 30, 150 + 150 * k), "left"), parse(word(text, 970, 150 + 150 * k), "right")]
    reading = interpret(labels, 1000, 800, CRS.from_epsg(32633))
    assert reading.hints is not None, reading.reason
    for x, y, e, n in reading.hints:
        assert e == pytest.approx(500000 + 1000 * (x - 150) / 150, abs=1e-6)
        assert n == pytest.approx(5540000 - 1000 * (y - 150) / 150, abs=1e-6)
