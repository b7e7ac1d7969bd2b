"""Results a person can read (issue 47): the coefficient sweep, the whirl branch and the
study print in a few lines, give a well-formed HTML table in a notebook, and ``.plot()``
returns a matplotlib Figure (drawn off screen, on the Agg canvas)."""

from __future__ import annotations

from html.parser import HTMLParser
from pathlib import Path

import matplotlib
import pytest
import tomlkit
from matplotlib.figure import Figure

from foilbearing.case import load_case
from foilbearing.constants import RPM
from foilbearing.errors import InputError

matplotlib.use("Agg")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


class _Tags(HTMLParser):
    """The open/close tag balance of an HTML fragment, and the tags it saw."""

    def __init__(self) -> None:
        super().__init__()
        self.stack: list[str] = []
        self.seen: list[str] = []

    def handle_starttag(self, tag: str, attrs: list) -> None:
        self.stack.append(tag)
        self.seen.append(tag)

    def handle_endtag(self, tag: str) -> None:
        assert self.stack and self.stack.pop() == tag, f"</{tag}> closes nothing open"


def _readable(result: object) -> str:
    text = repr(result)
    assert 2 <= len(text.splitlines()) <= 20, text
    parser = _Tags()
    parser.feed(result._repr_html_())  # type: ignore[attr-defined]
    parser.close()
    assert parser.stack == [] and "table" in parser.seen and "td" in parser.seen
    return text


@pytest.fixture(scope="module")
def rigid(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The rigid gas bearing example on 32 x 4 (onset near 10.4 krpm there)."""
    data = tomlkit.parse((EXAMPLES / "rigid_gas_bearing.toml").read_text(encoding="utf-8"))
    data["grid"]["n_theta"] = 32
    data["grid"]["n_z"] = 4
    path = tmp_path_factory.mktemp("rigid") / "rigid.toml"
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    return path


def test_a_coefficient_sweep_reads_in_a_few_lines_and_plots(rigid: Path) -> None:
    from foilbearing.coefficients import coefficients_over_speeds

    sweep = coefficients_over_speeds(load_case(rigid), ["10 krpm", "20 krpm"], ["200 Hz"])
    text = _readable(sweep)
    assert "rigid" in text and "speed" in text and "K XX" in text
    assert isinstance(sweep.plot(), Figure)


def test_a_whirl_branch_reads_in_a_few_lines_and_plots(rigid: Path) -> None:
    from foilbearing.bifurcation.bearing import whirl_branch

    scan = [7500 * RPM, 10000 * RPM, 12500 * RPM]
    branch = whirl_branch(load_case(rigid), scan=scan, steps=1)
    text = _readable(branch)
    assert branch.branch.bifurcation_type in text and "hopf speed" in text
    assert isinstance(branch.plot(), Figure)


def test_a_study_reads_in_a_few_lines_and_shows_its_figures(tmp_path: Path) -> None:
    from foilbearing.output.result import StudyResult

    png = tmp_path / "static_vs_speed.png"
    drawn = Figure(figsize=(2, 1))
    drawn.subplots().plot([0, 1], [1, 0])
    drawn.savefig(png, dpi=50)
    summary = {
        "case": "bump.toml",
        "stability": {"onset_speed_rpm": 64974.15, "whirl_frequency_Hz": 76.48, "grid": [96, 12]},
    }
    study = StudyResult(summary, tmp_path, {"static": (png,)})
    text = _readable(study)
    assert "onset speed 64974 rpm, whirl frequency 76.48 Hz" in text and "1 figures" in text
    shown = study.plot("static_vs_speed.png")
    assert isinstance(shown, Figure) and shown.get_size_inches()[0] == pytest.approx(1.0)
    with pytest.raises(InputError, match=r"static_vs_speed\.png"):
        study.plot("missing.png")
