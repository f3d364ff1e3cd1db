"""The basemap search on layers as they really are: smaller than the search area, stopping at a zoom a
plain template does not state, with 204/404 islands, through XYZ and WMS; and a place that fails is that
place's outcome, never the run's error. A real tile server on 127.0.0.1 (:mod:`hamta.bench.tileserver`)
serves the Landsat sample."""
import json

import numpy as np
import pytest

from hamta.bench.goals.basemap import rotated_target, zoom_resolution
from hamta.bench.tileserver import TileServer
from hamta.core import remote, run
from hamta.core.basemap.areas import PROBES
from hamta.core.basemap.coverage import Coverage, finest_zoom
from hamta.core.basemap.fetch import Fetcher
from hamta.core.basemap.services import parse_service
from hamta.core.basemap.tiles import tile_range
from hamta.core.basemap.zooms import search_bounds
from hamta.core.errors import InsufficientMatchesError, NoOverlapError
from hamta.core.matching.locate import Candidate
from hamta.core.options import RegisterOptions

CENTRE = (300.0, 300.0)  # Landsat source px: the island's middle
HOLE = (-8.62e6, 2.761e6, -8.59e6, 2.791e6)  # EPSG:3857: a 30 km square of the sample south-east of the target


@pytest.fixture(scope="module")
def server(landsat):
    tiles = TileServer(landsat, zmax=12, hole=HOLE).start()
    yield tiles
    tiles.stop()


@pytest.fixture(scope="module")
def case(landsat, tmp_path_factory):
    return rotated_target(landsat, str(tmp_path_factory.mktemp("coverage") / "target.png"), CENTRE, (320, 420),
                          2.0, 15.0)


def _rmse_px(case, result) -> float:
    grid = case.grid()
    _, mapped = result.map_points(grid)
    err = np.hypot(*(mapped - case.truth(grid)).T) / zoom_resolution(result.reference_service["zoom"])
    return float(np.sqrt(np.mean(err ** 2)))


def _search(case, url, tmp_path, factor, **options):
    fetcher = Fetcher(cache=str(tmp_path / "cache"), backoff_s=0.01)
    result, _ = run(case.path, url, None, options=RegisterOptions(extent=case.search_area(factor), **options),
                    fetcher=fetcher)
    return result, fetcher


@pytest.mark.split
@pytest.mark.parametrize("style", ["sparse", "islands"])
def test_a_layer_smaller_than_the_area_is_asked_only_near_its_data(style, case, server, tmp_path):
    """30 times the footprint's area: the sample covers about a third of the area's side, the rest answers
    404 or 204 (and, for 'islands', a 30 km hole in the data too). The photo is found, and the tiles
    asked for beyond the data are those of the first (coarsest) read and a tile's margin around the data."""
    result, fetcher = _search(case, server.xyz(style), tmp_path, 30.0)
    stats = result.reference_service["fetch"]
    assert result.verified, result.notes
    assert _rmse_px(case, result) <= 1.0
    assert stats["requests"] <= remote.SEARCH_REQUESTS, stats
    full = sum(tile_range(parse_service(server.xyz()), search_bounds(case.search_area(30.0),
                                                                              parse_service(server.xyz())), z).count
               for z in result.reference_service["zooms_read"])
    assert stats["missing"] < 0.25 * full, (stats, full)


def test_a_layer_that_stops_above_the_search_zooms_is_read_at_its_finest_zoom(landsat, tmp_path):
    """A plain template on a layer that ends at zoom 10, searched for a photo whose area the search would
    read at zooms 12-14: every read at 10 or coarser (the first asked for was four zooms finer), and a
    result, never an error of the layer's zooms; a rerun asks for no zoom beyond it."""
    target = rotated_target(landsat, str(tmp_path / "fine.png"), CENTRE, (480, 640), 8.0, 10.0)
    with TileServer(landsat, zmax=10) as tiles:
        result, fetcher = _search(target, tiles.xyz(), tmp_path, 2.0)
        service = result.reference_service
        assert max(service["zooms_read"]) == 10 and service["finest_zoom"] == 10, service
        assert not result.verified or _rmse_px(target, result) <= 1.0, result.notes
        assert any("SIFT" in p["found_by"] for p in service["places"]), service["places"]
        again, fetcher = _search(target, tiles.xyz(), tmp_path, 2.0)
        # the finest zoom is remembered, and the same places are tried: no tile is asked again
        assert fetcher.stats.missing == 0, fetcher.stats
        assert again.reference_service["zooms_read"][0] == service["zooms_read"][0] == 10


def test_the_finest_zoom_is_found_in_a_few_requests_and_remembered(landsat, tmp_path):
    with TileServer(landsat, zmax=13) as tiles:
        service = parse_service(tiles.xyz())
        point = (-8.6879e6, 2.8409e6)  # EPSG:3857, over the sample
        fetcher = Fetcher(cache=str(tmp_path / "cache"))
        assert finest_zoom(service, fetcher, point, 6, 19) == 13
        assert fetcher.stats.requests <= PROBES
        again = Fetcher(cache=str(tmp_path / "cache"))
        assert finest_zoom(service, again, point, 6, 19) == 13 and again.stats.requests == 0
        assert finest_zoom(service, Fetcher(cache=None), point, 6, 11) == 11  # the layer's stated limit holds


def test_a_finer_read_skips_the_tiles_far_from_the_data(tmp_path):
    """A first read whose right half is empty: at two zooms finer, tiles more than a tile of that first
    zoom from the data are not asked for; those outside the first read are (nothing is known there)."""
    from affine import Affine

    service = parse_service("http://127.0.0.1:1/{z}/{x}/{y}.png")
    z, res = 5, service.resolution(5)
    mask = np.zeros((512, 1024), bool)
    mask[:, :300] = True
    (ox, oy) = service.origin()
    coverage = Coverage(mask, Affine(res, 0, ox, 0, -res, oy), res * 256)
    wanted = coverage.wanted(service, tile_range(service, (ox + 1, oy - 512 * res + 1, ox + 1024 * res - 1, oy - 1),
                                                 z + 2))
    assert wanted.shape == (8, 16)
    columns = wanted.all(axis=0)
    assert columns[:9].all() and not columns[9:].any(), columns  # data to 1.17 tiles of zoom 5, plus one tile
    outside = coverage.wanted(service, tile_range(service, (ox + 2000 * res, oy - 100 * res, ox + 2100 * res, oy), z))
    assert outside.all()


def test_a_place_that_fails_is_that_places_outcome_and_the_search_goes_on(case, server, tmp_path, monkeypatch):
    """The first place found lies where the layer has no data, the second's registration finds that its read
    area misses it, with the place as its prior and without: both are noted, and the search goes on to the
    right place."""
    found = remote.candidates
    misses = []

    def with_bad_places(target, learned, image, valid, whole, structure=None):
        h, w = image.shape[:2]
        far = np.array([[0.2, 0.0, w - 40.0], [0.0, 0.2, h - 40.0]])  # a small place in the area's empty corner
        yield "SIFT", Candidate(far, 9, 9)
        yield from found(target, learned, image, valid, whole, structure)

    real = remote.register

    def missing_once(*args, **kwargs):
        if (kwargs.get("placed") is not None and not misses) or len(misses) == 1:  # with the place and without
            misses.append(1)
            raise NoOverlapError("The target raster 'x' and the reference raster '/cache/areas/area-1.tif' do not "
                                 "overlap according to their georeferencing. If the target's georeferencing is wrong, "
                                 "ignore it (CLI: --target-georef ignore) to search the whole reference.")
        return real(*args, **kwargs)

    monkeypatch.setattr(remote, "candidates", with_bad_places)
    monkeypatch.setattr(remote, "register", missing_once)
    result, _ = _search(case, server.xyz("sparse"), tmp_path, 30.0)
    places = result.reference_service["places"]
    assert result.verified, result.notes
    assert places[0]["outcome"] == "not read: the layer has no data there", places
    assert any(p["outcome"].startswith("not registered: the place's read area") for p in places), places
    assert places[-1]["outcome"] == "verified"
    text = json.dumps(places) + " ".join(result.notes)
    assert "--target-georef" not in text and "area-1.tif" not in text


def test_a_search_that_finds_nothing_lists_the_places_it_tried(case, server, tmp_path, monkeypatch):
    monkeypatch.setattr(remote, "register", _no_model)
    with pytest.raises(InsufficientMatchesError) as info:
        _search(case, server.xyz("sparse"), tmp_path, 5.0)
    message = str(info.value)
    assert "no model (too few agreeing points)" in message and "places tried" in message, message
    assert "areas" not in message


def _no_model(*args, **kwargs):
    raise InsufficientMatchesError("too few matches in '/cache/areas/area-2.tif'", 2, 4)


def test_a_wms_layer_smaller_than_the_area_is_searched_within_the_requests(case, server, tmp_path):
    source = f"crs=EPSG:3857&format=image/png&layers=photo&styles=&url={server.url}/wms"
    result, _ = _search(case, source, tmp_path, 30.0)
    stats = result.reference_service["fetch"]
    assert result.verified and _rmse_px(case, result) <= 1.0, result.notes
    assert stats["requests"] <= remote.SEARCH_REQUESTS, stats


def test_areas_are_counted_against_the_budget_before_they_are_read(landsat, tmp_path):
    """A reread area costs nothing; one past the budget is refused before any request, naming the cap; the
    plan is the same from a cold or a warm cache (the same verdicts on a rerun)."""
    from hamta.core.basemap.areas import AreaReader
    from hamta.core.basemap.fetch import ServiceError

    bounds = (-8.72e6, 2.80e6, -8.66e6, 2.86e6)  # EPSG:3857, inside the sample
    with TileServer(landsat, zmax=12) as tiles:
        service = parse_service(tiles.xyz())
        plans = []
        for _ in range(2):
            reader = AreaReader(service, Fetcher(cache=str(tmp_path / "cache")), 30)
            reader.read(bounds, 9, None)
            first = reader.planned
            assert reader.cost(bounds, 9) == 0
            reader.read(bounds, 9, None)
            assert reader.planned == first
            with pytest.raises(ServiceError, match="above the cap of 30 requests"):
                reader.read(bounds, 12, None)
            plans.append((first, reader.planned))
        assert plans[0] == plans[1] and plans[0][1] == first + PROBES, plans


def test_a_layer_with_data_everywhere_is_searched_within_the_requests(case, server, tmp_path, monkeypatch):
    """The worst case for the budget: every tile of every zoom an image (noise), an area 30 times the photo's
    side, a fetcher that allows 100 requests, and nothing found at the first zoom (the locating stubbed out):
    the next zoom would leave too few requests for the places, so it is left out and named; not found,
    within the requests."""
    monkeypatch.setattr(remote, "candidates", lambda *args, **kwargs: iter(()))
    fetcher = Fetcher(cache=str(tmp_path / "cache"), max_requests=100)
    with pytest.raises(InsufficientMatchesError) as info:
        run(case.path, server.xyz("texture"), None, fetcher=fetcher,
            options=RegisterOptions(extent=case.search_area(30.0 ** 2)))
    assert 0 < fetcher.stats.requests <= 100, fetcher.stats
    said = str(info.value)
    assert "Zoom 7 was not searched: its" in said and "of the 100 requests a search may send" in said, said


BAD_PLACES = {  # what a faulty locator may hand over (target working px -> area px), and the outcome noted
    "not finite": ([[np.nan, 0.0, 10.0], [0.0, 1.0, 10.0]], "not a finite 2 x 3 matrix"),
    "infinite": ([[np.inf, 0.0, 10.0], [0.0, 1.0, 10.0]], "not a finite 2 x 3 matrix"),
    "flat": ([[0.0, 0.0, 10.0], [0.0, 0.0, 10.0]], "flat or mirrored"),
    "mirrored": ([[-0.2, 0.0, 300.0], [0.0, 0.2, 10.0]], "flat or mirrored"),
    "a dot": ([[1e-9, 0.0, 10.0], [0.0, 1e-9, 10.0]], "footprint would be 0 area px"),
    "the world": ([[1e6, 0.0, 10.0], [0.0, 1e6, 10.0]], "area px across"),
}


def test_no_candidate_ends_a_search(case, server, tmp_path, monkeypatch):
    """Degenerate placements are refused as such, a place whose registration raises (a bug) is that place's
    outcome, and the search goes on to the right place."""
    found = remote.candidates
    raised = []

    def with_faults(target, learned, image, valid, whole, structure=None):
        for matrix, _ in BAD_PLACES.values():
            yield "SIFT", Candidate(np.array(matrix), 9, 9)
        yield from found(target, learned, image, valid, whole, structure)

    real = remote.register

    def raising_once(*args, **kwargs):
        if kwargs.get("placed") is not None and not raised:
            raised.append(1)
            raise ValueError("math domain error")
        return real(*args, **kwargs)

    monkeypatch.setattr(remote, "candidates", with_faults)
    monkeypatch.setattr(remote, "register", raising_once)
    result, _ = _search(case, server.xyz("sparse"), tmp_path, 30.0)
    outcomes = [p["outcome"] for p in result.reference_service["places"]]
    assert result.verified, result.notes
    for (_, expected), outcome in zip(BAD_PLACES.values(), outcomes):
        assert outcome.startswith("not tried: its ") and expected in outcome, outcomes
    assert outcomes[len(BAD_PLACES)].startswith("failed: internal error (ValueError: math domain error)"), outcomes
    assert outcomes[-1] == "verified"


def test_a_locator_that_fails_ends_that_zoom_noted_not_the_search(case, server, tmp_path, monkeypatch):
    found = remote.candidates
    calls = []

    def failing_first(*args, **kwargs):
        calls.append(1)
        if len(calls) == 1:
            raise ZeroDivisionError("division by zero")
        yield from found(*args, **kwargs)

    monkeypatch.setattr(remote, "candidates", failing_first)
    result, _ = _search(case, server.xyz("sparse"), tmp_path, 30.0)
    assert any("failed: internal error (ZeroDivisionError" in n for n in result.notes), result.notes
    assert len(calls) >= 2


def test_a_place_that_gives_nothing_with_its_prior_is_registered_without_it(case, server, tmp_path, monkeypatch):
    """A locator's place is coarse: where the registration that starts from it gives nothing, the place's area
    is registered again at any turn and scale, and that result is kept."""
    real = remote.register
    ways = []

    def no_model_from_a_prior(*args, **kwargs):
        ways.append("prior" if kwargs.get("placed") is not None else "free")
        if kwargs.get("placed") is not None:
            raise InsufficientMatchesError("too few matches", 2, 8)
        return real(*args, **kwargs)

    monkeypatch.setattr(remote, "register", no_model_from_a_prior)
    result, _ = _search(case, server.xyz("sparse"), tmp_path, 5.0)
    assert result.verified and _rmse_px(case, result) <= 1.0, result.notes
    assert result.reference_service["places"][-1]["outcome"] == "verified"
    assert ways.count("prior") >= 1 and ways[ways.index("prior") + 1] == "free", ways
    assert remote.SEARCH_TRIES == 1 + 2 * (remote.MAX_PLACES + 1)
