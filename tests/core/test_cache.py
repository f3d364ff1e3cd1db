"""Hamta's cache cannot be turned against its user, and a cache that fails only costs a refetch: a
warning and no cache, never a failed run (:mod:`hamta.core.basemap.cache`)."""
import os
import stat

import pytest

from hamta.bench.tileserver import TileServer
from hamta.cli.main import main
from hamta.core import run
from hamta.core.basemap import tiles
from hamta.core.basemap.cache import Cache
from hamta.core.basemap.fetch import Fetcher
from hamta.core.errors import InputError


@pytest.fixture(scope="module")
def server(landsat):
    tiles = TileServer(landsat, zmax=12).start()
    yield tiles
    tiles.stop()


def _register(landsat_crop, server, cache):
    fetcher = Fetcher(cache=None if cache is None else str(cache))
    result, _ = run(landsat_crop.path, server.xyz(), None, fetcher=fetcher)
    assert result.verified, result.notes
    return result, fetcher


def _files(folder):
    return sorted(os.path.join(d, f) for d, _, files in os.walk(folder) for f in files)


def test_a_new_cache_is_private_and_a_rerun_sends_no_request(landsat_crop, server, tmp_path):
    cache = tmp_path / "new" / "cache"
    _register(landsat_crop, server, cache)
    assert stat.S_IMODE(os.lstat(cache).st_mode) == 0o700
    for d, dirs, _ in os.walk(cache):
        for name in dirs:
            assert stat.S_IMODE(os.lstat(os.path.join(d, name)).st_mode) == 0o700
    result, fetcher = _register(landsat_crop, server, cache)
    assert fetcher.stats.requests == 0 and not fetcher.warnings


@pytest.mark.parametrize("where", ["a file", "under /proc", "writable by others", "another user's"])
def test_an_unusable_or_unsafe_cache_is_named_in_one_warning_and_the_run_goes_on(where, landsat_crop, server, tmp_path):
    cache = tmp_path / "cache"
    if where == "a file":
        cache.write_text("not a folder")
    elif where == "under /proc":
        cache = "/proc/hamta-cache"
    elif where == "writable by others":
        cache.mkdir()
        os.chmod(cache, 0o777)
    else:
        if os.getuid() != 0:
            pytest.skip("giving a folder to another user needs root")
        cache.mkdir(mode=0o700)
        os.chown(cache, 65534, 65534)
    before = _files(tmp_path)
    result, fetcher = _register(landsat_crop, server, cache)
    warnings = [n for n in result.notes if "cache folder" in n]
    assert len(warnings) == 1 and str(cache) in warnings[0], result.notes
    assert fetcher.stats.requests > 0 and _files(tmp_path) == before  # nothing was written into it


def test_planted_links_in_the_cache_are_never_written_through(landsat_crop, server, tmp_path):
    cache, victim = tmp_path / "cache", tmp_path / "victim"
    cache.mkdir(mode=0o700)
    victim.mkdir()
    (cache / "areas").symlink_to(victim)
    (cache / "http").symlink_to(victim)
    result, _ = _register(landsat_crop, server, cache)
    assert not os.listdir(victim)
    assert any("symbolic link" in n for n in result.notes), result.notes


def test_a_cached_answer_that_no_longer_decodes_is_dropped_and_fetched_again(landsat_crop, server, tmp_path):
    cache = tmp_path / "cache"
    _register(landsat_crop, server, cache)
    entries = _files(cache / "http")
    for path in entries:
        with open(path, "wb") as f:
            f.write(b"\x89PNG garbage")
    for path in _files(cache / "areas"):
        with open(path, "wb") as f:
            f.write(b"II*\x00 not a tiff")
    result, fetcher = _register(landsat_crop, server, cache)
    assert fetcher.stats.requests == len(entries)
    assert all(tiles.decode_tile("", open(p, "rb").read(), 256).shape == (4, 256, 256) for p in entries)


def test_a_full_cache_disk_keeps_the_area_for_this_run_only(landsat_crop, server, tmp_path, monkeypatch):
    write = tiles._write

    def full(path, *args):
        if path.startswith(str(tmp_path)):
            raise OSError(28, "No space left on device")
        return write(path, *args)

    monkeypatch.setattr(tiles, "_write", full)
    result, _ = _register(landsat_crop, server, tmp_path / "cache")
    assert any("could not be kept in the cache" in n for n in result.notes), result.notes


def test_cache_reads_never_follow_links_and_refuse_oversized_entries(tmp_path):
    warnings = []
    store = Cache.open(str(tmp_path / "c"), warnings)
    secret = tmp_path / "secret"
    secret.write_bytes(b"private")
    link = os.path.join(store.folder("http"), "entry")
    os.symlink(secret, link)
    assert store.read(link, 100) is None and not os.path.lexists(link) and secret.read_bytes() == b"private"
    big = os.path.join(store.folder("http"), "big")
    with open(big, "wb") as f:
        f.write(b"x" * 101)
    assert store.read(big, 100) is None and not os.path.exists(big)
    assert not warnings


def test_outputs_inside_the_cache_or_led_out_of_the_batch_folder_by_a_link_are_refused(landsat_crop, server, tmp_path,
                                                                                       monkeypatch, capsys):
    cache = tmp_path / "cache"
    monkeypatch.setenv("HAMTA_CACHE", str(cache))
    assert main(["register", "--target", landsat_crop.path, "--reference", server.xyz(), "--out",
                 str(cache / "out"), "--quiet"]) == 2
    assert "inside Hamta's cache" in capsys.readouterr().err
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    out.mkdir()
    elsewhere.mkdir()
    (out / "link").symlink_to(elsewhere)
    jobs = tmp_path / "jobs.csv"
    jobs.write_text(f"target,reference,output\n{landsat_crop.path},{server.xyz()},link/pair\n")
    with pytest.raises(InputError, match="symbolic link"):
        from hamta.core.batch import read_jobs
        read_jobs(str(jobs), str(out))
    assert main(["batch", str(jobs), "--out", str(out), "--workers", "1", "--quiet"]) != 0
    assert not os.listdir(elsewhere)
