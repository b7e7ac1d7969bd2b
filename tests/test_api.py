"""The public Python API: ``import foilbearing as fb`` and the command line's quick start."""

from __future__ import annotations

import subprocess
import sys

import pytest

import foilbearing as fb


def test_the_package_and_the_command_line_load_no_numerics_until_asked() -> None:
    """``import foilbearing`` and ``foilbearing --help`` load neither pint, SciPy, numba nor
    matplotlib (the numerics are imported on first use), and choose no matplotlib backend."""
    code = (
        "import sys, contextlib, io\n"
        "import foilbearing, foilbearing.cli.main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n"
        "        foilbearing.cli.main.main(['--help'])\n"
        "    except SystemExit:\n"
        "        pass\n"
        "heavy = ('pint', 'scipy', 'numba', 'matplotlib', 'xarray', 'dask')\n"
        "print(','.join(m for m in heavy if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_public_names_resolve_to_the_library_functions() -> None:
    """Every name in ``fb.__all__`` resolves, to the object of the module that defines it."""
    from foilbearing import orbit, stability, static

    for name in fb.__all__:
        assert getattr(fb, name) is not None
    assert fb.solve_equilibrium is static.solve_equilibrium
    assert fb.onset_speed is stability.onset_speed
    assert fb.simulate is orbit.simulate
    assert fb.RPM * 30.0 == pytest.approx(3.141592653589793)
    with pytest.raises(AttributeError, match="no attribute 'solve'"):
        _ = fb.solve  # type: ignore[attr-defined]


def test_the_api_quick_start_carries_the_load() -> None:
    """The docstring's quick start on a coarse grid: the film force balances the static load
    (the equilibrium's defining balance, to its solver tolerance), and the coefficients at the
    equilibrium give a positive direct stiffness."""
    from dataclasses import replace

    from foilbearing.case import Grid

    case = replace(
        fb.default_case().with_voltages(150.0),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )
    st = fb.solve_equilibrium(case, speed=50_000 * fb.RPM)
    assert st.converged
    fx, fy = st.force  # on the journal, N; the load W acts along +X: F + W = 0
    load = case.operation.load
    assert fx == pytest.approx(-load, rel=1e-6)
    assert abs(fy) < 1e-6 * load
    fc = fb.force_coefficients(st, [st.speed])
    assert fc.K[0, 0, 0] > 0 and fc.K[0, 1, 1] > 0
