"""Results a person can read: a short ``repr`` with the headline numbers and their units,
an HTML table for notebooks, and ``.plot()`` returning a matplotlib Figure (32 × 4 grid)."""

from __future__ import annotations

from dataclasses import replace
from html.parser import HTMLParser

import matplotlib
import pytest

import foilbearing as fb
from foilbearing.case import Grid
from foilbearing.output.display import format_value, split_unit, summary_text
from foilbearing.static import StaticResult

matplotlib.use("Agg")
from matplotlib.figure import Figure

#: A printed result stays a glance, not a dump (the dataclass repr was 7-23 k characters).
MAX_REPR = 1500


class _Tags(HTMLParser):
    """The start and end tags of a document, to check they nest."""

    def __init__(self) -> None:
        super().__init__()
        self.open: list[str] = []
        self.seen: set[str] = set()
        self.cells: list[str] = []

    def handle_starttag(self, tag: str, attrs: object) -> None:
        self.open.append(tag)
        self.seen.add(tag)

    def handle_endtag(self, tag: str) -> None:
        assert self.open and self.open.pop() == tag, f"</{tag}> closes nothing open"

    def handle_data(self, data: str) -> None:
        if self.open and self.open[-1] == "td":
            self.cells.append(data)


def _table_cells(html: str) -> list[str]:
    parser = _Tags()
    parser.feed(html)
    parser.close()
    assert parser.open == [], f"unclosed tags {parser.open}"
    assert {"table", "tr", "td"} <= parser.seen
    return parser.cells


@pytest.fixture(scope="module")
def case() -> fb.Case:
    grid = Grid(n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None)
    case = replace(fb.default_case().with_voltages(150.0), grid=grid, disturbance=None)
    return replace(case, rotor=replace(case.rotor, imbalance=1e-6))


@pytest.fixture(scope="module")
def static(case: fb.Case) -> StaticResult:
    return fb.solve_equilibrium(case, speed="30 krpm")


def test_units_are_read_off_the_key_suffix() -> None:
    assert split_unit("min_film_um") == ("min film", "µm")
    assert split_unit("C_Ns_per_m") == ("C", "N·s/m")
    assert split_unit("K_N_per_m") == ("K", "N/m")
    assert split_unit("speed_rpm") == ("speed", "rpm")
    assert split_unit("eccentricity") == ("eccentricity", "")
    text = summary_text("t", {"speed_rpm": 30000.0, "load_N": 8.8, "ok": True, "x": None})
    assert text.splitlines()[1:] == [
        "  speed  30000 rpm",
        "  load   8.8 N",
        "  ok     yes",
        "  x      –",
    ]


def test_a_static_result_prints_its_headline_in_a_few_lines(static: StaticResult) -> None:
    text = repr(static)
    assert len(text) < MAX_REPR
    h = static.headline()
    assert f"eccentricity  {format_value(h['eccentricity'])}" in text
    assert f"min film      {format_value(h['min_film_um'])} µm" in text
    assert "30000 rpm" in text and "32 × 4" in text and "converged     yes" in text
    cells = _table_cells(static._repr_html_())
    assert format_value(h["eccentricity"]) in cells and "µm" in cells
    assert isinstance(static.plot(), Figure)


def test_coefficients_print_k_and_c_with_units(static: StaticResult) -> None:
    fc = fb.force_coefficients(static, [static.speed, 0.5 * static.speed])
    text = repr(fc)
    assert len(text) < MAX_REPR
    k_xx = fc.headline()["K_N_per_m"][0][0][0]
    assert "N/m" in text and "N·s/m" in text and format_value(k_xx) in text
    assert "frequency        [500, 250] Hz" in text
    _table_cells(fc._repr_html_())
    assert isinstance(fc.plot(), Figure)


def test_the_onset_prints_speed_and_whirl_frequency(case: fb.Case) -> None:
    on = fb.onset_speed(case, [rpm * fb.RPM for rpm in (20e3, 40e3, 60e3, 80e3)])
    assert on.onset_speed is not None
    text = repr(on)
    assert len(text) < MAX_REPR
    h = on.headline()
    assert f"whirl frequency  {format_value(h['whirl_frequency_Hz'])} Hz" in text
    assert f"onset speed      {format_value(h['onset_speed_rpm'])} rpm" in text
    _table_cells(on._repr_html_())
    assert isinstance(on.plot(), Figure)


def test_a_constant_speed_orbit_prints_its_one_x_amplitude(case: fb.Case) -> None:
    run = fb.simulate(
        case, fb.constant_speed("30 krpm", 0.01), settings=fb.OrbitSettings(steps_per_rev=32)
    )
    text = repr(run)
    assert len(text) < MAX_REPR
    from foilbearing.orbit.analysis import synchronous_amplitude

    sync = synchronous_amplitude(run)
    assert sync is not None
    one_x = ", ".join(format_value(a * 1e6) for a in sync[0])
    assert f"one x amplitude 0pk  [{one_x}] µm" in text
    assert "status               completed" in text
    cells = _table_cells(run._repr_html_())
    assert "completed" in cells
    assert isinstance(run.plot(), Figure)


def test_a_grid_check_prints_its_table_and_each_readouts_error() -> None:
    from foilbearing.check import READOUTS, GridCheck

    values: dict[str, list[float | None]] = {key: [None, None] for key, _, _ in READOUTS}
    values["eccentricity"] = [0.30, 0.31]
    values["min_film_um"] = [20.0, 19.0]
    check = GridCheck("rigid", ((24, 4), (48, 8)), 2, 0.0, "none", values, (0.1, 0.4))
    text = repr(check)
    assert len(text) < MAX_REPR and "24 × 4, 48 × 8" in text
    assert "-3.23 %" in text  # (0.30 - 0.31)/0.31, the case's grid against the finer
    cells = _table_cells(check._repr_html_())
    assert "[0.3, 0.31, error -3.23 %]" in cells and "µm" in cells
