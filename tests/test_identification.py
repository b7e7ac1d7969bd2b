"""Identification of the PZT stack parameters (paper section 4, Eqs. 1-2).

The shipped example files are SYNTHETIC: ``scripts/make_measurements.py`` writes
them from the paper's fitted values with a fixed seed and stated Gaussian
noise σ, so the test knows the generating parameters and the noise, and its
tolerances are 4 standard errors computed from σ and the design matrix.
"""

from __future__ import annotations

import importlib.util
import io
import json
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
import tomlkit
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from foilbearing.errors import InputError
from foilbearing.identification import (
    NoLoadData,
    StiffnessData,
    case_values,
    example_measurements,
    fit_no_load,
    fit_stiffness,
    identify,
    read_no_load,
    read_stiffness,
    update_case_file,
)
from foilbearing.units import parse_quantity

ROOT = Path(__file__).resolve().parents[1]
NO_LOAD, STIFFNESS = example_measurements()
DATA = NO_LOAD.parent
AREA = 3.54e-4  # m², stinger-foil contact area (paper section 4)
UM = 1e-6


@pytest.fixture(scope="module")
def gen() -> ModuleType:
    """The generating script, imported from its file (it is not part of the package)."""
    spec = importlib.util.spec_from_file_location(
        "make_measurements", ROOT / "scripts" / "make_measurements.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _write_no_load(path: Path, voltage: np.ndarray, columns: list[np.ndarray]) -> Path:
    header = ",".join(["voltage_V"] + [f"stack{i + 1}_um" for i in range(len(columns))])
    rows = [
        ",".join(repr(float(x)) for x in (v, *(c[k] for c in columns)))
        for k, v in enumerate(voltage)
    ]
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return path


def _write_stiffness(path: Path, stiffness: list[float], d33: tuple[float, float]) -> Path:
    """Noiseless stiffness test: δ = D33,1 V² + D33,2 V − F/K_p (µm in the file)."""
    rows = ["stack,voltage_V,load_N,displacement_um"]
    for i, k in enumerate(stiffness):
        for v in (0.0, 50.0, 100.0, 150.0):
            for f in np.linspace(0.0, 20.0, 6):
                d = (d33[0] * v**2 + d33[1] * v - f / k) / UM
                rows.append(f"{i + 1},{v!r},{float(f)!r},{float(d)!r}")
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


# ------------------------------------------------------------ published values


def test_shipped_files_are_what_the_script_writes(gen: ModuleType, tmp_path: Path) -> None:
    gen.make(tmp_path)
    for name in ("stack_no_load.csv", "stack_stiffness.csv"):
        assert (tmp_path / name).read_bytes() == (DATA / name).read_bytes(), (
            f"{name} is stale: rerun python scripts/make_measurements.py"
        )


def test_example_files_recover_generating_parameters(gen: ModuleType) -> None:
    ident = identify(NO_LOAD, STIFFNESS, AREA)
    meta = ident.no_load_data.metadata
    assert "SYNTHETIC" in NO_LOAD.read_text() and "SYNTHETIC" in STIFFNESS.read_text()
    assert int(meta["seed"]) == gen.SEED and float(meta["noise_sigma_um"]) == gen.NO_LOAD_SIGMA_UM

    # No load: cov(c) = σ² (XᵀX)⁻¹ per stack, X = [V², V]; every stack shares the voltages,
    # so the pooled estimate is the mean of the per-stack ones and its covariance is 1/3 of that.
    sigma = gen.NO_LOAD_SIGMA_UM * UM
    v = np.asarray(gen.NO_LOAD_VOLTAGES_V)
    x = np.column_stack([v**2, v])
    se = sigma * np.sqrt(np.diag(np.linalg.inv(x.T @ x)))
    n_stacks = len(gen.STACK_SCALE)
    pooled = ident.no_load.pooled
    assert abs(pooled.d33_1 - gen.D33_1_UM_PER_V2 * UM) < 4 * se[0] / np.sqrt(n_stacks)
    assert abs(pooled.d33_2 - gen.D33_2_UM_PER_V * UM) < 4 * se[1] / np.sqrt(n_stacks)
    for i, s in enumerate(ident.no_load_data.stacks):
        d1, d2 = gen.stack_coefficients(i)
        assert abs(ident.no_load.stacks[s].d33_1 - d1 * UM) < 4 * se[0]
        assert abs(ident.no_load.stacks[s].d33_2 - d2 * UM) < 4 * se[1]
    # Residual SD of each stack's fit estimates σ (15 degrees of freedom: within ±50 %).
    for q in ident.no_load.stacks.values():
        assert 0.5 * sigma < q.residual_std < 1.5 * sigma
    assert pooled.r_squared > 0.99

    # Stiffness: slope SE = σ/√Sxx per line; K_p = −1/slope, so SE(K_p) ≈ K_p² σ/√Sxx;
    # a stack's K_p is the mean over its 4 voltages, the headline the mean over stacks.
    f = np.asarray(gen.STIFFNESS_LOADS_N)
    n_v = len(gen.STIFFNESS_VOLTAGES_V)
    slope_se = gen.STIFFNESS_SIGMA_UM * UM / np.sqrt(np.sum((f - f.mean()) ** 2))
    k_true = np.asarray(gen.STACK_STIFFNESS_N_PER_M)
    k_se = k_true**2 * slope_se / np.sqrt(n_v)
    for i, s in enumerate(ident.stiffness_data.stacks):
        assert abs(ident.stiffness.stack_stiffness[s] - k_true[i]) < 4 * k_se[i]
        assert ident.stiffness.stack_stiffness_se[s] == pytest.approx(k_se[i], rel=0.5)
    mean_se = np.sqrt(np.sum(k_se**2)) / k_true.size
    assert abs(ident.stiffness.mean_stiffness - k_true.mean()) < 4 * mean_se
    assert abs(ident.stiffness.k_p - k_true.mean() / AREA) < 4 * mean_se / AREA

    head = ident.headline()
    json.dumps(head)  # JSON-ready
    assert head["d33_1_um_per_V2"] == pytest.approx(pooled.d33_1 / UM)
    assert head["k_p_N_per_m3"] == pytest.approx(ident.stiffness.k_p)
    assert set(head["per_stack"]) == {"1", "2", "3"}
    assert 72.0 <= min(p["stroke_150V_um"] for p in head["per_stack"].values())
    assert max(p["stroke_150V_um"] for p in head["per_stack"].values()) <= 78.0


def test_paper_stack_displacements_from_its_coefficients(tmp_path: Path) -> None:
    """Paper section 4: δ = −0.0028 V² + 0.9122 V gives 38.61 / 63.22 / 73.83 µm."""
    v = np.arange(0.0, 151.0, 10.0)
    y = -0.0028 * v**2 + 0.9122 * v
    fit = fit_no_load(read_no_load(_write_no_load(tmp_path / "paper.csv", v, [y, y, y])))
    got = fit.pooled.displacement(np.array([50.0, 100.0, 150.0])) / UM
    np.testing.assert_allclose(got, [38.61, 63.22, 73.83], atol=0.01)
    assert fit.linear.d33_um_per_V > 0.467  # the stacks out-stroke the manufacturer's line


def test_noiseless_data_recovered_exactly(tmp_path: Path) -> None:
    v = np.linspace(-20.0, 200.0, 12)
    coefficients = [(-3.1e-3, 0.87), (-2.2e-3, 0.95)]
    columns = [a * v**2 + b * v for a, b in coefficients]
    fit = fit_no_load(read_no_load(_write_no_load(tmp_path / "nl.csv", v, columns)))
    for (a, b), q in zip(coefficients, fit.stacks.values(), strict=True):
        assert q.d33_1_um_per_V2 == pytest.approx(a, rel=1e-10)
        assert q.d33_2_um_per_V == pytest.approx(b, rel=1e-10)
        assert q.r_squared == pytest.approx(1.0, abs=1e-12)
    # Same voltages for every stack: the pooled fit is the mean of the per-stack fits.
    assert fit.pooled.d33_1_um_per_V2 == pytest.approx(-2.65e-3, rel=1e-10)
    assert fit.pooled.d33_2_um_per_V == pytest.approx(0.91, rel=1e-10)

    k = [0.43e6, 0.5e6]
    data = read_stiffness(_write_stiffness(tmp_path / "st.csv", k, (-2.8e-9, 0.91e-6)))
    sfit = fit_stiffness(data, AREA)
    for s, ki in zip(data.stacks, k, strict=True):
        assert sfit.stack_stiffness[s] == pytest.approx(ki, rel=1e-10)
    for line in sfit.lines:
        expected = -2.8e-9 * line.voltage**2 + 0.91e-6 * line.voltage
        assert line.intercept == pytest.approx(expected, rel=1e-10, abs=1e-15)
    assert sfit.mean_stiffness == pytest.approx(np.mean(k), rel=1e-10)


def test_contact_stiffness_per_area(tmp_path: Path) -> None:
    """Paper: K_p = 0.46e6 N/m over A_c = 3.54e-4 m² gives k_p = 1.30e9 N/m³."""
    data = read_stiffness(_write_stiffness(tmp_path / "st.csv", [0.46e6] * 3, (-2.8e-9, 0.91e-6)))
    k_p = fit_stiffness(data, AREA).k_p
    assert float(f"{k_p:.3g}") == 1.30e9


# ------------------------------------------------------------------- bad files

NO_LOAD_OK = "voltage_V,stack1_um\n0,0\n50,38\n100,63\n"
BAD_FILES = [
    # (id, reader, text or None for a missing file, fragments the message must contain)
    ("missing-column", read_no_load, "volts,stack1_um\n0,0\n50,38\n100,63\n", ["line 1", "voltage_V"]),
    ("unexpected-column", read_no_load, "voltage_V,stack1_um,temp\n0,0,1\n", ["line 1", "column 3", "temp"]),
    ("no-stack-column", read_no_load, "voltage_V\n0\n50\n100\n", ["line 1", "stack<label>_um"]),
    ("text", read_no_load, "# c\nvoltage_V,stack1_um\n0,0\n50,abc\n100,63\n", ["line 4", "'stack1_um'", "abc"]),
    ("nan", read_no_load, "voltage_V,stack1_um\n0,0\nnan,38\n100,63\n", ["line 3", "'voltage_V'", "finite"]),
    ("inf", read_no_load, "voltage_V,stack1_um\n0,0\n50,inf\n100,63\n", ["line 3", "'stack1_um'", "finite"]),
    ("too-few", read_no_load, "voltage_V,stack1_um\n\n50,38\n100,63\n", ["lines 3-4", "'voltage_V'", "≥ 3"]),
    ("all-zero", read_no_load, "voltage_V,stack1_um\n0,0\n0,1\n0,2\n", ["lines 2-4", "'voltage_V'", "zero"]),
    ("one-voltage", read_no_load, "voltage_V,stack1_um\n0,0\n50,1\n50,2\n", ["lines 2-4", "'voltage_V'", "50 V"]),
    ("huge-voltage", read_no_load, "voltage_V,stack1_um\n0,0\n1e300,1\n5,2\n", ["line 3", "'voltage_V'"]),
    ("field-count", read_no_load, "voltage_V,stack1_um\n0,0\n50,38,7\n100,63\n", ["line 3", "3 fields"]),
    ("repeated-header", read_no_load, "voltage_V,stack1_um,stack1_um\n0,0,0\n", ["line 1", "column 3"]),
    ("empty", read_no_load, "", ["empty"]),
    ("comments-only", read_stiffness, "# only a comment\n\n", ["empty"]),
    ("not-utf8", read_no_load, "voltage_V,stack1_um\n0,\udcff\n", ["UTF-8"]),
    ("missing-file", read_no_load, None, ["no such"]),
    ("st-missing-column", read_stiffness, "stack,voltage_V,load_N\n1,0,0\n", ["line 1", "displacement_um"]),
    ("st-no-rows", read_stiffness, "stack,voltage_V,load_N,displacement_um\n", ["line 1", "no data rows"]),
    ("st-negative-load", read_stiffness, "stack,voltage_V,load_N,displacement_um\n1,0,0,0\n1,0,-2,-4\n",
     ["line 3", "'load_N'", "-2"]),
    ("st-one-load", read_stiffness, "stack,voltage_V,load_N,displacement_um\n1,0,0,0\n1,0,2,-4\n1,50,2,30\n",
     ["line(s) 4", "'load_N'", "stack 1 at 50 V"]),
    ("st-text", read_stiffness, "stack,voltage_V,load_N,displacement_um\n1,0,0,0\n1,0,2 N,-4\n",
     ["line 3", "'load_N'", "2 N"]),
    ("st-empty-label", read_stiffness, "stack,voltage_V,load_N,displacement_um\n,0,0,0\n1,0,2,-4\n",
     ["line 2", "'stack'"]),
]  # fmt: skip


@pytest.mark.parametrize(
    ("reader", "text", "fragments"), [c[1:] for c in BAD_FILES], ids=[c[0] for c in BAD_FILES]
)
def test_bad_files_name_file_line_and_column(
    tmp_path: Path, reader: Callable[[Path], object], text: str | None, fragments: list[str]
) -> None:
    path = tmp_path / "bad.csv"
    if text is not None:
        path.write_bytes(text.encode("utf-8", errors="surrogateescape"))
    with pytest.raises(InputError) as info:
        reader(path)
    message = str(info.value)
    assert message.startswith(str(path)) and "\n" not in message
    for fragment in fragments:
        assert fragment in message


def test_rising_displacement_and_bad_area(tmp_path: Path) -> None:
    path = tmp_path / "st.csv"
    path.write_text("stack,voltage_V,load_N,displacement_um\n2,50,0,30\n2,50,10,35\n")
    with pytest.raises(InputError, match=r"st\.csv: stack 2 at 50 V: .*does not fall"):
        fit_stiffness(read_stiffness(path), AREA)
    with pytest.raises(InputError, match="contact_area"):
        identify(NO_LOAD, STIFFNESS, 0.0)


# Mostly well-formed rows (as many fields as the header, numeric-looking tokens) so that
# both the parsing and the checking paths are reached, plus free text and odd characters.
_NUMBERS = ["0", "0", "50", "100", "150", "2", "20", "1e3", "-3"]
_ODD = ["1e400", "nan", "inf", "abc", "", " ", '"', "#", "\r", "\x00", "é", "1_0", "2 N"]
_TOKENS = st.sampled_from(_NUMBERS) | st.sampled_from(_ODD) | st.text(max_size=4)
_HEADERS = st.sampled_from(
    [
        "voltage_V,stack1_um,stack2_um",
        "voltage_V,stack1_um",
        "stack,voltage_V,load_N,displacement_um",
        "stack,voltage_V,load_N,displacement_um,extra",
        "voltage_V,voltage_V",
        "",
        "# seed: 3",
    ]
)


@st.composite
def _csv_text(draw: st.DrawFn) -> str:
    header = draw(_HEADERS)
    width = header.count(",") + 1
    numeric = st.lists(st.sampled_from(_NUMBERS), min_size=width, max_size=width)
    odd = st.lists(_TOKENS, min_size=width, max_size=width) | st.lists(_TOKENS, max_size=6)
    rows = draw(st.lists(numeric.map(",".join), max_size=10))
    for _ in range(draw(st.integers(0, 2))):  # a few odd lines at random places
        rows.insert(draw(st.integers(0, len(rows))), ",".join(draw(odd)))
    return "\n".join([header, *rows, draw(st.just("") | st.text(max_size=20))])


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(text=_csv_text())
def test_random_csv_parses_or_raises_input_error(text: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "random.csv"
        path.write_text(text, encoding="utf-8", errors="surrogateescape")
        for reader in (read_no_load, read_stiffness):
            try:
                data = reader(path)
            except InputError as exc:
                assert str(exc).startswith(str(path))
            else:
                assert np.all(np.isfinite(data.displacement))
                try:  # what parses also fits, or says why not
                    if isinstance(data, NoLoadData):
                        assert np.isfinite(fit_no_load(data).pooled.d33_2)
                    else:
                        assert isinstance(data, StiffnessData)
                        assert np.isfinite(fit_stiffness(data, AREA).k_p)
                except InputError as exc:
                    assert str(exc).startswith(str(path))


# ------------------------------------------------------------------- case file

CASE = """\
# The paper's bearing (a comment that must survive).
[bearing]
radius = "20 mm"

[actuators]
angles = ["60 deg", "180 deg", "300 deg"]
d33_quadratic = -2.8e-9  # m/V², paper Table 2
stack_stiffness = "0.46e6 N/m"
contact_area = "3.54e-4 m**2"
"""


def test_update_case_file_round_trips(tmp_path: Path) -> None:
    ident = identify(NO_LOAD, STIFFNESS, AREA)
    case = tmp_path / "case.toml"
    case.write_text(CASE, encoding="utf-8")
    update_case_file(case, ident)
    text = case.read_text(encoding="utf-8")
    assert "# The paper's bearing (a comment that must survive)." in text
    assert "# m/V², paper Table 2" in text
    act = tomlkit.parse(text)["actuators"]
    assert dict(act) | case_values(ident) == dict(act)  # written as these strings
    assert act["angles"] == ["60 deg", "180 deg", "300 deg"]
    assert act["contact_area"] == "3.54e-4 m**2"
    read_back = {
        "d33_quadratic": (parse_quantity(act["d33_quadratic"], "length_per_voltage2", field="x"), ident.no_load.pooled.d33_1),
        "d33_linear": (parse_quantity(act["d33_linear"], "length_per_voltage", field="x"), ident.no_load.pooled.d33_2),
        "stack_stiffness": (parse_quantity(act["stack_stiffness"], "stiffness", field="x"), ident.stiffness.mean_stiffness),
    }  # fmt: skip
    for key, (got, want) in read_back.items():
        assert got == pytest.approx(want, rel=1e-4), key  # 5 significant figures written
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]  # no temporary left


def test_update_case_file_without_actuators_table(tmp_path: Path) -> None:
    case = tmp_path / "case.toml"
    case.write_text("[bearing]\nradius = 0.02\n", encoding="utf-8")
    with pytest.raises(InputError, match=r"case\.toml: no \[actuators\] table"):
        update_case_file(case, identify(NO_LOAD, STIFFNESS, AREA))
    assert case.read_text(encoding="utf-8") == "[bearing]\nradius = 0.02\n"


# ---------------------------------------------------------------------- plots


def test_plots_return_figures() -> None:
    from foilbearing.output.plots.identification import plot_no_load, plot_stiffness

    ident = identify(NO_LOAD, STIFFNESS, AREA)
    fig = plot_no_load(ident.no_load_data, ident.no_load)
    (ax,) = fig.axes
    assert len(ax.lines) == 2 * 3 + 2  # points + fit per stack, pooled fit, manufacturer
    fig.savefig(io.BytesIO(), format="png")
    fig = plot_stiffness(ident.stiffness_data, ident.stiffness)
    ax_line, ax_bar = fig.axes
    assert len(ax_line.lines) == 2 * 4  # points + line per voltage of stack 1
    assert len(ax_bar.patches) == 3 and len(ax_bar.lines) >= 1
    fig.savefig(io.BytesIO(), format="png")


def test_identification_does_not_import_matplotlib() -> None:
    code = "import sys, foilbearing.identification; assert 'matplotlib' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)
