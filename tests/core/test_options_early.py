"""Options checked before any work (issue 25): GDAL creation options, a nodata value that does not fit the
pixel type, usage messages in the flags users type, bad job lists; each refused with nothing written."""
import pytest

from hamta.cli.main import main


@pytest.mark.parametrize("extra,says", [
    (["--co", "COMPRESS=BOGUS"], "COMPRESS=BOGUS: GDAL's GTIFF driver says"),
    (["--co", "NOSUCHOPTION=1"], "does not support creation option NOSUCHOPTION"),
    (["--format", "cog", "--co", "NOSUCH=1"], "does not support creation option NOSUCH"),
    (["--format", "vrt", "--co", "COMPRESS=ZSTD"], "not to a warped VRT"),
    (["--fill", "nodata", "--nodata", "300"], "nodata 300 does not fit the pixel type"),
    (["--fill", "nodata", "--nodata", "2.5"], "nodata 2.5 does not fit the pixel type"),
    (["--tolerance", "-1"], "--tolerance must be"),
    (["--max-working-pixels", "5"], "--max-working-pixels must be"),
])
def test_bad_output_options_are_usage_errors_before_any_work(tmp_path, small_pair, capsys, extra, says):
    out = tmp_path / "out"
    rc = main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out", str(out),
               "--method", "sift", "--quiet", *extra])
    err = capsys.readouterr().err
    assert rc == 2 and says in err, err
    assert not out.exists() or not list(out.iterdir())


def test_good_creation_options_are_applied(tmp_path, small_pair):
    import rasterio

    out = tmp_path / "out"
    assert main(["register", "--reference", small_pair["reference"], "--target", small_pair["target"], "--out",
                 str(out), "--method", "sift", "--quiet", "--co", "COMPRESS=LZW"]) == 0
    with rasterio.open(out / "registered.tif") as ds:
        assert ds.compression.name.lower() == "lzw"


@pytest.mark.parametrize("header,row,says", [
    ("target,reference,model", "{t},{r},bogus", "Row 1 of the job list '{jobs}': unknown model 'bogus'"),
    ("target,reference,method", "{t},{r},nosuch", "Row 1 of the job list '{jobs}': unknown method 'nosuch'"),
])
def test_a_bad_job_row_is_refused_before_any_work(tmp_path, small_pair, capsys, header, row, says):
    jobs = tmp_path / "jobs.csv"
    jobs.write_text(f"{header}\n{row.format(t=small_pair['target'], r=small_pair['reference'])}\n")
    rc = main(["batch", str(jobs), "--out", str(tmp_path / "out"), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 1 and says.format(jobs=jobs) in err and "Traceback" not in err, err
    assert not (tmp_path / "out").exists()


def test_a_missing_job_list_is_named_as_missing(tmp_path, capsys):
    rc = main(["batch", str(tmp_path / "nope.csv"), "--out", str(tmp_path / "out"), "--quiet"])
    assert rc == 1 and "does not exist" in capsys.readouterr().err
