"""What a result that did not verify tells the user to try, in each front end's words."""
from types import SimpleNamespace

from hamta.core.advice import advice, spelled


def _result(verified=False, mode="georeferenced", error=0.8, bound=3.4, model="affine", local=False):
    check = SimpleNamespace(verified=verified, error_px=error, error_bound_px=bound, tolerance_px=3.0)
    return SimpleNamespace(verification=check, plan=SimpleNamespace(mode=mode), options={"model": model,
                                                                                         "local": local})


def test_each_option_that_may_help_is_named_with_its_value():
    tips = advice(_result())
    assert [(t.option, t.value) for t in tips] == [("target_georef", "ignore"), ("tolerance_px", 3.4),
                                                    ("model", "polynomial-2"), ("local", True),
                                                    ("accept_unverified", True)]
    assert [spelled(t).split(" (")[0] for t in tips] == ["--target-georef ignore", "--tolerance 3.4",
                                                         "--model polynomial-2", "--local", "--accept-unverified"]
    assert spelled(tips[3]) == "--local (QGIS: 'Local (non-rigid) correction')"


def test_only_what_applies_is_suggested():
    tips = advice(_result(mode="search", error=4.0, model="tps", local=True))
    assert [t.option for t in tips] == ["extent", "accept_unverified"]  # an error beyond the tolerance: not the
    # tolerance; a search: a closer search area
    assert spelled(tips[0]) == "--extent xmin,ymin,xmax,ymax (QGIS: 'Search area')"
    assert advice(_result(verified=True)) == []
