"""Identification of the PZT stack parameters from measured stack data (paper section 4).

Two tests identify the stack model of Eqs. (1)-(2), ``δ = F/K_p + D33,1 V² + D33,2 V``:

- the no-load test (paper Fig. 5b) gives D33,1 and D33,2 from a least-squares fit
  through the origin of ``δ = D33,1 V² + D33,2 V``, per stack and pooled;
- the stiffness test (paper Figs. 6b-c) gives the stack stiffness K_p from the
  slope ``−1/K_p`` of displacement against compressive load at each voltage;
  ``k_p = K_p / A_c`` (N/m³) with A_c the stinger-foil contact area.

Files are CSV with a header line; lines starting with ``#`` are comments, and
comments of the form ``# key: value`` are kept as metadata. Columns:

- no-load: ``voltage_V``, then one ``stack<label>_um`` column per stack (µm);
- stiffness (long format): ``stack``, ``voltage_V``, ``load_N`` (≥ 0,
  compressive), ``displacement_um``.

Everything inside is SI (m, V, N); the fit objects offer µm views for reports.
R² is everywhere the usual ``1 − SS_res/SS_tot`` with SS_tot the sum of squares
about the mean, also for the fits through the origin (where it may be negative).
"""

from __future__ import annotations

import csv
import math
import os
import re
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import tomlkit
import tomlkit.exceptions
from tomlkit.items import Item

from foilbearing.errors import InputError

__all__ = [
    "MANUFACTURER_D33",
    "Identification",
    "LineFit",
    "LinearFit",
    "NoLoadData",
    "NoLoadFit",
    "QuadraticFit",
    "StiffnessData",
    "StiffnessFit",
    "case_values",
    "fit_no_load",
    "fit_stiffness",
    "identify",
    "read_no_load",
    "read_stiffness",
    "update_case_file",
]

FloatArray = npt.NDArray[np.float64]
PathLike = str | os.PathLike[str]

#: Manufacturer's linear piezoelectric coefficient of the stacks, m/V (paper Table 1).
MANUFACTURER_D33 = 0.467e-6
_UM = 1e-6
_MAX_VOLTAGE = 1e4  # V; far above any PZT stack, and it keeps V² finite in the fit
_STACK_COLUMN = re.compile(r"stack(\w+)_um")
_META = re.compile(r"#\s*([A-Za-z_]\w*)\s*:\s*(.*?)\s*$")
_STIFFNESS_COLUMNS = ("stack", "voltage_V", "load_N", "displacement_um")


@dataclass(frozen=True)
class NoLoadData:
    """No-load test: stack displacement against voltage (paper Fig. 5b).

    ``displacement[i]`` belongs to stack ``stacks[i]`` (label ``"1"`` for column
    ``stack1_um``); ``metadata`` holds the file's ``# key: value`` comments.
    """

    voltage: FloatArray  #: driving voltage, V, shape (n,)
    displacement: FloatArray  #: stack displacement, m, shape (n_stacks, n)
    stacks: tuple[str, ...]
    source: str = ""
    metadata: dict[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class StiffnessData:
    """Stiffness test: displacement against compressive load at fixed voltages (Fig. 6b).

    One entry per reading (long format); ``line`` is its line number in the file.
    """

    stack: npt.NDArray[np.str_]  #: stack label, shape (n,)
    voltage: FloatArray  #: V, shape (n,)
    load: FloatArray  #: compressive load, N, ≥ 0, shape (n,)
    displacement: FloatArray  #: m, shape (n,)
    line: npt.NDArray[np.int_]
    source: str = ""
    metadata: dict[str, str] = field(default_factory=dict)

    @property
    def stacks(self) -> tuple[str, ...]:
        """Stack labels in order of first appearance."""
        return tuple(dict.fromkeys(self.stack.tolist()))

    def groups(self) -> list[tuple[str, float, npt.NDArray[np.bool_]]]:
        """``(stack, voltage, mask)`` for each stack and voltage, in file order."""
        keys = dict.fromkeys(zip(self.stack.tolist(), self.voltage.tolist(), strict=True))
        return [(s, v, (self.stack == s) & (self.voltage == v)) for s, v in keys]


@dataclass
class _Table:
    """A CSV file split into a header and data rows, each row with its line number."""

    source: str
    header_line: int = 0
    names: list[str] = field(default_factory=list)
    rows: list[tuple[int, list[str]]] = field(default_factory=list)
    metadata: dict[str, str] = field(default_factory=dict)

    def fail(self, message: str, line: int | None = None, column: str | None = None) -> InputError:
        where = [f"line {line}"] * (line is not None) + [f"column {column!r}"] * (
            column is not None
        )
        return InputError(
            f"{', '.join(where)}: {message}" if where else message, source=self.source
        )

    def span(self) -> str:
        return f"lines {self.rows[0][0]}-{self.rows[-1][0]}" if self.rows else "no data lines"

    def numbers(self, name: str) -> FloatArray:
        """Column ``name`` as floats; text, NaN and inf are errors naming line and column."""
        k = self.names.index(name)
        out = np.empty(len(self.rows))
        for i, (line, fields) in enumerate(self.rows):
            try:
                out[i] = float(fields[k])
            except ValueError:
                raise self.fail(f"{fields[k]!r} is not a number", line, name) from None
            if not math.isfinite(out[i]):
                raise self.fail(f"{fields[k]!r} is not finite", line, name)
        if name == "voltage_V" and (bad := np.flatnonzero(np.abs(out) > _MAX_VOLTAGE)).size:
            line = self.rows[bad[0]][0]
            raise self.fail(f"{out[bad[0]]:g} V is beyond ±{_MAX_VOLTAGE:g} V", line, name)
        return out

    def check_header(
        self, allowed: str, required: tuple[str, ...], pattern: re.Pattern[str]
    ) -> None:
        for name in required:
            if name not in self.names:
                found = ", ".join(self.names)
                raise self.fail(
                    f"no column {name!r} (found {found}); expected {allowed}", self.header_line
                )
        for k, name in enumerate(self.names):
            if name not in required and pattern.fullmatch(name) is None:
                message = f"column {k + 1}: unexpected column {name!r}; expected {allowed}"
                raise self.fail(message, self.header_line)


def _read_table(path: PathLike, what: str) -> _Table:
    table = _Table(str(path))
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise table.fail(f"no such {what} file") from None
    except UnicodeDecodeError as exc:
        raise table.fail(f"not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise table.fail(f"cannot read the {what} file ({exc.strerror})") from None
    for number, raw in enumerate(text.split("\n"), start=1):
        line = raw.strip()
        if line.startswith("#"):
            if (match := _META.match(line)) is not None:
                table.metadata[match.group(1)] = match.group(2)
            continue
        if not line:
            continue
        try:
            fields = [f.strip() for f in next(csv.reader([line]))]
        except (csv.Error, StopIteration) as exc:
            raise table.fail(f"not valid CSV ({exc})", number) from None
        if not table.names:
            table.header_line, table.names = number, fields
            for k, name in enumerate(fields):
                if not name or fields.index(name) != k:
                    raise table.fail(
                        f"column {k + 1}: header name {name!r} empty or repeated", number
                    )
        elif len(fields) != len(table.names):
            header = f"the header (line {table.header_line}) has {len(table.names)}"
            message = f"{len(fields)} fields where {header}"
            raise table.fail(message, number)
        else:
            table.rows.append((number, fields))
    if not table.names:
        raise table.fail(f"empty {what} file: no header line and no data")
    return table


def read_no_load(path: PathLike) -> NoLoadData:
    """Read a no-load test file (columns ``voltage_V``, ``stack<label>_um`` ...).

    Raises
    ------
    InputError
        Naming the file, line and column: missing or empty file, missing or
        unexpected column, text/NaN/inf where a number belongs, a voltage beyond
        ±10 kV, fewer than 3 readings, fewer than 2 distinct non-zero voltages.
    """
    table = _read_table(path, "no-load")
    allowed = "voltage_V and one stack<label>_um column per stack (um)"
    table.check_header(allowed, ("voltage_V",), _STACK_COLUMN)
    stacks = tuple(m.group(1) for n in table.names if (m := _STACK_COLUMN.fullmatch(n)))
    if not stacks:
        raise table.fail(f"no stack<label>_um column; expected {allowed}", table.header_line)
    voltage = table.numbers("voltage_V")
    displacement = np.array([table.numbers(f"stack{s}_um") for s in stacks]) * _UM
    if len(table.rows) < 3:
        message = f"{len(table.rows)} data rows ({table.span()}); δ = D33,1 V² + D33,2 V needs ≥ 3"
        raise table.fail(message, column="voltage_V")
    if (nonzero := np.unique(voltage[voltage != 0.0])).size < 2:
        which = "all voltages are zero" if nonzero.size == 0 else f"only {nonzero[0]:g} V"
        message = f"{table.span()}: {which}; the fit needs ≥ 2 distinct non-zero voltages"
        raise table.fail(message, column="voltage_V")
    return NoLoadData(voltage, displacement, stacks, table.source, table.metadata)


def read_stiffness(path: PathLike) -> StiffnessData:
    """Read a stiffness test file (``stack``, ``voltage_V``, ``load_N``, ``displacement_um``).

    Raises
    ------
    InputError
        Naming the file, line and column: as :func:`read_no_load`, plus an empty
        stack label, a negative load, or fewer than 2 distinct loads for a stack
        at a voltage.
    """
    table = _read_table(path, "stiffness")
    table.check_header(
        "the columns " + ", ".join(_STIFFNESS_COLUMNS), _STIFFNESS_COLUMNS, re.compile("(?!)")
    )
    if not table.rows:
        raise table.fail(f"no data rows after the header on line {table.header_line}")
    k = table.names.index("stack")
    for line, fields in table.rows:
        if not fields[k]:
            raise table.fail("empty stack label", line, "stack")
    stack = np.array([fields[k] for _, fields in table.rows])
    voltage, load = table.numbers("voltage_V"), table.numbers("load_N")
    displacement = table.numbers("displacement_um") * _UM
    lines = np.array([line for line, _ in table.rows])
    if (negative := np.flatnonzero(load < 0.0)).size:
        i = negative[0]
        raise table.fail(
            f"{load[i]:g} N is negative; the compressive load must be ≥ 0", lines[i], "load_N"
        )
    data = StiffnessData(stack, voltage, load, displacement, lines, table.source, table.metadata)
    for s, v, mask in data.groups():
        if (n := np.unique(load[mask]).size) < 2:
            where = ", ".join(map(str, lines[mask]))
            message = (
                f"stack {s} at {v:g} V has {n} distinct load on line(s) {where}; a slope needs ≥ 2"
            )
            raise table.fail(message, column="load_N")
    return data


def _least_squares(
    design: FloatArray, y: FloatArray
) -> tuple[FloatArray, FloatArray, float, float]:
    """Least squares ``y ≈ design @ c``: coefficients, standard errors, R², residual SD.

    Standard errors are ``sqrt(diag(s² (XᵀX)⁻¹))`` with ``s² = SS_res/(n − p)``,
    NaN when n = p; R² = 1 − SS_res/SS_tot, SS_tot about the mean of ``y``.
    """
    n, p = design.shape
    coef = np.asarray(np.linalg.lstsq(design, y, rcond=None)[0], dtype=np.float64)
    ss_res = float(np.sum((y - design @ coef) ** 2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0.0 else math.nan
    s2 = ss_res / (n - p) if n > p else math.nan
    se: FloatArray = np.sqrt(s2 * np.diag(np.linalg.pinv(design.T @ design)))
    return coef, se, r2, math.sqrt(s2)


@dataclass(frozen=True)
class QuadraticFit:
    """``δ = D33,1 V² + D33,2 V`` fitted through the origin (paper Eq. 2), SI units."""

    d33_1: float  #: m/V²
    d33_2: float  #: m/V
    d33_1_se: float  #: standard error of d33_1, m/V²
    d33_2_se: float  #: standard error of d33_2, m/V
    r_squared: float
    residual_std: float  #: sqrt(SS_res/(n − 2)), m
    n_points: int

    @property
    def d33_1_um_per_V2(self) -> float:
        """D33,1 in µm/V²."""
        return self.d33_1 / _UM

    @property
    def d33_2_um_per_V(self) -> float:
        """D33,2 in µm/V."""
        return self.d33_2 / _UM

    def displacement(self, voltage: npt.ArrayLike) -> FloatArray:
        """Fitted no-load displacement (m) at ``voltage`` (V), any shape."""
        v = np.asarray(voltage, dtype=float)
        return np.asarray(self.d33_1 * v**2 + self.d33_2 * v)


@dataclass(frozen=True)
class LinearFit:
    """``δ = D33 V`` through the origin, to compare with the manufacturer's 0.467 µm/V."""

    d33: float  #: m/V
    d33_se: float  #: m/V
    r_squared: float

    @property
    def d33_um_per_V(self) -> float:
        """D33 in µm/V."""
        return self.d33 / _UM


@dataclass(frozen=True)
class NoLoadFit:
    """No-load identification: pooled and per-stack quadratic fits, pooled linear fit."""

    pooled: QuadraticFit
    stacks: dict[str, QuadraticFit]
    linear: LinearFit
    source: str = ""


def fit_no_load(data: NoLoadData) -> NoLoadFit:
    """Fit ``δ = D33,1 V² + D33,2 V`` through the origin, per stack and pooled (Eq. 2).

    The pooled fit treats the readings of all stacks as one data set (the
    paper's representative curve, R² = 0.9926 there); so is the linear fit
    ``δ = D33 V``. With all stacks at the same voltages the pooled coefficients
    are the mean of the per-stack ones.
    """

    def quadratic(v: FloatArray, y: FloatArray) -> QuadraticFit:
        c, se, r2, sd = _least_squares(np.column_stack([v**2, v]), y)
        return QuadraticFit(float(c[0]), float(c[1]), float(se[0]), float(se[1]), r2, sd, y.size)

    v_all = np.tile(data.voltage, len(data.stacks))
    y_all = data.displacement.ravel()
    c, se, r2, _ = _least_squares(v_all[:, None], y_all)
    return NoLoadFit(
        pooled=quadratic(v_all, y_all),
        stacks={
            s: quadratic(data.voltage, data.displacement[i]) for i, s in enumerate(data.stacks)
        },
        linear=LinearFit(float(c[0]), float(se[0]), r2),
        source=data.source,
    )


@dataclass(frozen=True)
class LineFit:
    """Straight line ``δ = δ0 + slope·F`` of one stack at one voltage (Fig. 6b)."""

    stack: str
    voltage: float  #: V
    slope: float  #: dδ/dF, m/N
    slope_se: float  #: m/N; NaN for two loads
    intercept: float  #: δ0, displacement at zero load, m
    r_squared: float
    n_points: int

    @property
    def stiffness(self) -> float:
        """K_p = −1/slope, N/m."""
        return -1.0 / self.slope

    @property
    def stiffness_se(self) -> float:
        """Standard error of K_p to first order, ``slope_se/slope²``, N/m."""
        return self.slope_se / self.slope**2


@dataclass(frozen=True)
class StiffnessFit:
    """Stack stiffness identification (paper Figs. 6b-c).

    ``stack_stiffness[s]`` is K_p of stack ``s`` (N/m), the mean of −1/slope over
    its voltages; ``contact_area`` is A_c (m²).
    """

    lines: tuple[LineFit, ...]
    stack_stiffness: dict[str, float]
    stack_stiffness_se: dict[str, float]
    contact_area: float
    source: str = ""

    @property
    def mean_stiffness(self) -> float:
        """K_p averaged over the stacks, N/m (0.46e6 N/m in the paper)."""
        return float(np.mean(list(self.stack_stiffness.values())))

    @property
    def mean_stiffness_se(self) -> float:
        """Standard error of :attr:`mean_stiffness` (stacks independent), N/m."""
        se = np.array(list(self.stack_stiffness_se.values()))
        return float(np.sqrt(np.sum(se**2)) / se.size)

    @property
    def k_p(self) -> float:
        """Stack stiffness per unit contact area K_p/A_c, N/m³ (1.30e9 in the paper)."""
        return self.mean_stiffness / self.contact_area


def _check_area(contact_area: float) -> float:
    if not (math.isfinite(contact_area) and contact_area > 0.0):
        raise InputError(f"contact_area = {contact_area!r} m²: must be a positive finite area")
    return float(contact_area)


def fit_stiffness(data: StiffnessData, contact_area: float) -> StiffnessFit:
    """Fit the slope −1/K_p of displacement against load per stack and voltage.

    ``contact_area`` is the stinger-foil contact area A_c, m² (3.54e-4 m² in the paper).

    Raises
    ------
    InputError
        If a displacement does not fall with load (slope ≥ 0), or the area is not positive.
    """
    area = _check_area(contact_area)
    fits = []
    for s, v, mask in data.groups():
        f, y = data.load[mask], data.displacement[mask]
        c, se, r2, _ = _least_squares(np.column_stack([np.ones_like(f), f]), y)
        if not c[1] < 0.0:
            slope = f"slope {c[1] / _UM:+.4g} um/N"
            message = f"stack {s} at {v:g} V: displacement does not fall with load ({slope})"
            raise InputError(message + "; K_p needs a negative slope", source=data.source)
        fits.append(LineFit(s, v, float(c[1]), float(se[1]), float(c[0]), r2, int(f.size)))
    stiffness, stiffness_se = {}, {}
    for s in data.stacks:
        mine = [fit for fit in fits if fit.stack == s]
        stiffness[s] = float(np.mean([fit.stiffness for fit in mine]))
        stiffness_se[s] = math.sqrt(sum(fit.stiffness_se**2 for fit in mine)) / len(mine)
    return StiffnessFit(tuple(fits), stiffness, stiffness_se, area, data.source)


@dataclass(frozen=True)
class Identification:
    """Both identifications with their data, ready for reports and the case file."""

    no_load_data: NoLoadData
    no_load: NoLoadFit
    stiffness_data: StiffnessData
    stiffness: StiffnessFit

    def headline(self) -> dict[str, Any]:
        """Headline values with unit-named keys (JSON-ready); pooled values at top level."""
        p, st = self.no_load.pooled, self.stiffness
        per_stack: dict[str, dict[str, float]] = {
            s: {
                "d33_1_um_per_V2": q.d33_1_um_per_V2,
                "d33_2_um_per_V": q.d33_2_um_per_V,
                "r_squared": q.r_squared,
                "stroke_150V_um": float(q.displacement(150.0)) / _UM,
            }
            for s, q in self.no_load.stacks.items()
        }
        for s, k in st.stack_stiffness.items():
            per_stack.setdefault(s, {})["stack_stiffness_N_per_m"] = k
        return {
            "d33_1_um_per_V2": p.d33_1_um_per_V2,
            "d33_1_se_um_per_V2": p.d33_1_se / _UM,
            "d33_2_um_per_V": p.d33_2_um_per_V,
            "d33_2_se_um_per_V": p.d33_2_se / _UM,
            "r_squared": p.r_squared,
            "d33_linear_um_per_V": self.no_load.linear.d33_um_per_V,
            "d33_linear_r_squared": self.no_load.linear.r_squared,
            "d33_manufacturer_um_per_V": MANUFACTURER_D33 / _UM,
            "stack_stiffness_N_per_m": st.mean_stiffness,
            "stack_stiffness_se_N_per_m": st.mean_stiffness_se,
            "contact_area_m2": st.contact_area,
            "k_p_N_per_m3": st.k_p,
            "per_stack": per_stack,
            "no_load_file": self.no_load.source,
            "stiffness_file": st.source,
        }


def identify(
    no_load_path: PathLike, stiffness_path: PathLike, contact_area: float
) -> Identification:
    """Read both test files (formats in the module docstring) and identify D33,1, D33,2,
    K_p and k_p = K_p/A_c; ``contact_area`` is A_c, m² (3.54e-4 m² in the paper)."""
    area = _check_area(contact_area)
    no_load_data, stiffness_data = read_no_load(no_load_path), read_stiffness(stiffness_path)
    return Identification(
        no_load_data, fit_no_load(no_load_data), stiffness_data, fit_stiffness(stiffness_data, area)
    )


def case_values(identification: Identification) -> dict[str, str]:
    """The case's ``[actuators]`` entries as quantity strings (5 significant figures)."""
    p, st = identification.no_load.pooled, identification.stiffness
    return {
        "d33_quadratic": f"{p.d33_1_um_per_V2:.5g} um/V**2",
        "d33_linear": f"{p.d33_2_um_per_V:.5g} um/V",
        "stack_stiffness": f"{st.mean_stiffness / 1e6:.5g}e6 N/m",
    }


def update_case_file(case_path: PathLike, identification: Identification) -> None:
    """Write d33_quadratic, d33_linear and stack_stiffness into the case's ``[actuators]``.

    The file is edited with tomlkit, so comments and layout are kept (an inline
    comment on a replaced key stays); it is written atomically (a temporary file
    in the same directory, then ``os.replace``).

    Raises
    ------
    InputError
        If the file cannot be read, is not valid TOML, or has no ``[actuators]`` table.
    """
    path, source = Path(case_path), str(case_path)
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            doc = tomlkit.parse(fh.read())
    except (OSError, UnicodeDecodeError, tomlkit.exceptions.ParseError) as exc:
        raise InputError(f"cannot read the case file as TOML ({exc})", source=source) from None
    table = doc.get("actuators")
    if not isinstance(table, dict):
        message = "no [actuators] table to receive d33_quadratic, d33_linear, stack_stiffness"
        raise InputError(message, source=source)
    for key, text in case_values(identification).items():
        new, old = tomlkit.string(text), table.get(key)
        if isinstance(old, Item):
            new.trivia.indent, new.trivia.comment = old.trivia.indent, old.trivia.comment
            new.trivia.comment_ws = old.trivia.comment_ws
        table[key] = new
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(doc.as_string())
            fh.flush()
            os.fsync(fh.fileno())
        shutil.copymode(path, tmp)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
