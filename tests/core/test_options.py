"""Every option is declared once (core/options.py) and reachable, with the same default, from
``hamta register`` and ``hamta batch`` (the Processing side: tests/qgis/test_processing.py)."""
import pytest

from hamta.cli.main import build_parser
from hamta.cli.options import settings_from
from hamta.core.options import LABEL_CHARS, OutputOptions, RegisterOptions, cli_flag, option_fields
from tests.conftest import option_samples

COMMANDS = {"register": ["register", "--reference", "r.tif", "--target", "t.tif", "--out", "o"],
            "batch": ["batch", "jobs.csv", "--out", "o"]}


def _argv(f, spec, value):
    if isinstance(value, bool):
        return [cli_flag(f, spec)]
    return [cli_flag(f, spec), value[0] if isinstance(value, tuple) else str(value)]


@pytest.mark.parametrize("command", COMMANDS)
def test_the_command_line_defaults_are_the_options_defaults(command):
    options, output = settings_from(build_parser().parse_args(COMMANDS[command]))
    assert options == RegisterOptions() and output == OutputOptions()


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("sample", option_samples(), ids=lambda s: s[0].name)
def test_every_option_is_reachable_from_the_command_line(command, sample):
    f, spec, value = sample
    options, output = settings_from(build_parser().parse_args(COMMANDS[command] + _argv(f, spec, value)))
    got = getattr(options if hasattr(options, f.name) else output, f.name)
    assert got == value


def test_every_option_has_help_a_short_label_and_a_flag_of_its_own():
    flags = []
    for cls in (RegisterOptions, OutputOptions):
        for f, spec in option_fields(cls):
            assert spec.help and 0 < len(spec.label) <= LABEL_CHARS, f.name
            assert f.default is not None or spec.unset, f"{f.name}: say what leaving it empty means"
            flags.append(cli_flag(f, spec))
    assert len(flags) == len(set(flags))


def test_bench_variants_set_flags_as_written():
    """``auto[local=1]`` (README, docs/benchmarks.md) sets the flag; a value that is not a flag is refused."""
    from hamta.bench.runner import parse_variant

    _, _, options = parse_variant("auto[local=1]")
    assert RegisterOptions(**options).local is True
    assert RegisterOptions(pixel_mode="false").pixel_mode is False
    with pytest.raises(ValueError, match="local must be true or false"):
        RegisterOptions(local=2)
