"""What a run reports moves forward only (core/progress.py): the fraction never goes back, a stage's
counter counts on over the run, a log gets one line per stage; cancellation still stops it."""
import random
import threading

import pytest

from hamta.core.errors import RegistrationCanceled
from hamta.core.progress import Forward, Monitor, stage_name


def recorder():
    seen = []
    return seen, lambda fraction, message: seen.append((round(fraction, 6), message))


def test_the_fraction_never_goes_back():
    seen, progress = recorder()
    run = Monitor(progress)
    search, write = run.span(0.0, 0.8), run.span(0.8, 1.0)
    search.span(0.5, 1.0).report(0.5, "matching")  # 0.6
    search.span(0.0, 0.5).report(1.0, "reading")  # 0.4: a stage whose span begins below what was reported
    write.report(0.0, "writing")  # 0.8
    search.report(0.2, "verifying")  # 0.16
    assert seen == [(0.6, "matching"), (0.6, "reading"), (0.8, "writing"), (0.8, "verifying")]


def test_a_monitor_inside_a_span_is_held_forward_too():
    """:func:`hamta.core.pipeline.register` builds its own monitor on a span of the run's."""
    seen, progress = recorder()
    run = Monitor(progress)
    stage = run.span(0.0, 0.5)
    inner = Monitor(lambda f, m: stage.report(f, m))
    inner.report(0.8, "matching")
    inner.span(0.0, 0.5).report(1.0, "reading")  # back to 0.5 of the inner span: held at 0.8
    assert [f for f, _ in seen] == [0.4, 0.4] and [m for _, m in seen] == ["matching", "reading"]


def test_a_stage_counter_counts_on_over_the_run():
    seen, progress = recorder()
    run = Monitor(progress)
    for n, span in ((10, run.span(0.0, 0.2)), (16, run.span(0.3, 0.5))):  # two reads of tiles, as a search does
        for i in range(1, n + 1):
            span.report(i / n, f"fetching tiles {i}/{n}")
        run.span(0.2, 0.3).report(0.5, "locating the target at zoom 7")
    messages = [m for _, m in seen]
    assert messages[:10] == [f"fetching tiles {i}/10" for i in range(1, 11)]
    assert messages[11:27] == [f"fetching tiles {10 + i}/26" for i in range(1, 17)]
    assert messages[10] == messages[27] == "locating the target at zoom 7"


def test_forward_twice_is_forward_once():
    """A counter already counted on (a nested monitor's) is passed as it is."""
    seen, progress = recorder()
    outer = Forward(progress)
    inner = Forward(outer)
    for n in (4, 3):
        for i in range(1, n + 1):
            inner(0.1 * i, f"fetching tiles {i}/{n}")
    assert [m for _, m in seen][-1] == "fetching tiles 7/7"
    assert [m for _, m in seen] == [f"fetching tiles {i}/4" for i in range(1, 5)] + [
        f"fetching tiles {4 + i}/7" for i in range(1, 4)]


def test_a_late_report_of_the_same_count_does_not_restart_it():
    seen, progress = recorder()
    forward = Forward(progress)
    for i in (1, 2, 4, 3, 5):  # threads: 3 arrives after 4
        forward(0.1 * i, f"pairs {i}/5")
    assert [m for _, m in seen] == ["pairs 1/5", "pairs 2/5", "pairs 4/5", "pairs 5/5"]  # 3 said nothing new


def test_nothing_new_is_not_said_again():
    seen, progress = recorder()
    run = Monitor(progress)
    for _ in range(3):
        run.report(0.5, "verifying")
    run.report(0.4, "verifying")  # held at 0.5: the same report
    run.report(0.6, "verifying")
    assert seen == [(0.5, "verifying"), (0.6, "verifying")]


def test_reports_from_threads_reach_the_front_end_in_order():
    seen, progress = recorder()
    run = Monitor(progress)

    def work(seed):
        rng = random.Random(seed)
        for _ in range(300):
            run.report(rng.random(), "verifying")

    threads = [threading.Thread(target=work, args=(seed,)) for seed in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    fractions = [f for f, _ in seen]
    assert fractions == sorted(fractions) and len(set(fractions)) == len(fractions) > 5


def test_stage_name_drops_the_counter_only():
    assert stage_name("fetching tiles 3/16") == "fetching tiles"
    assert stage_name("locating the target at zoom 12") == "locating the target at zoom 12"
    assert stage_name("3/10 pairs, 1 failed, ~20 s left") == "3/10 pairs, 1 failed, ~20 s left"
    assert stage_name("") == "" and stage_name(None) == ""


def test_cancel_and_silence_still_work():
    seen, progress = recorder()
    canceled = []
    run = Monitor(progress, lambda: bool(canceled))
    run.silent().report(0.9, "beside")
    run.report(0.1, "reading")
    canceled.append(True)
    with pytest.raises(RegistrationCanceled):
        run.span(0.5, 1.0).report(0.5, "matching")
    assert seen == [(0.1, "reading")]
