"""The core install has no ROSS (``pip install foilbearing``; ``foilbearing[ross]`` adds the
rotor and the export): the package and every non-rotor command work without it, and a rotor
command says in one line how to add it (exit 2).

ROSS is blocked in a subprocess by a ``ross`` package first on the path whose import raises
ImportError, as a missing package does.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RIGID = ROOT / "examples" / "rigid_gas_bearing.toml"
ROTOR = ROOT / "examples" / "rotor_rigid_symmetric.toml"


@pytest.fixture(scope="module")
def no_ross(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """The environment of a subprocess in which ``import ross`` fails."""
    block = tmp_path_factory.mktemp("no_ross")
    (block / "ross").mkdir()
    (block / "ross" / "__init__.py").write_text(
        "raise ImportError('ross is blocked: the core install has no ROSS')\n"
    )
    env = dict(os.environ)
    path = [str(block), str(ROOT / "src"), env.get("PYTHONPATH", "")]
    env["PYTHONPATH"] = os.pathsep.join(p for p in path if p)
    return env


def _run(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "foilbearing", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )


def test_ross_is_blocked(no_ross: dict[str, str]) -> None:
    """The premise: in this environment ``import ross`` raises ImportError."""
    out = subprocess.run(
        [sys.executable, "-c", "import ross"], capture_output=True, text=True, env=no_ross
    )
    assert out.returncode == 1 and "ross is blocked" in out.stderr


def test_the_package_and_the_film_commands_need_no_ross(
    no_ross: dict[str, str], tmp_path: Path
) -> None:
    code = "import foilbearing, foilbearing.static, foilbearing.export.ross, foilbearing.rotor"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=no_ross)
    assert out.returncode == 0, out.stderr
    assert _run(no_ross, "case", "show", str(RIGID)).returncode == 0
    coarse = (
        RIGID.read_text().replace("n_theta = 96", "n_theta = 32").replace("n_z = 12", "n_z = 4")
    )
    case = tmp_path / "rigid_coarse.toml"
    case.write_text(coarse)
    out = _run(no_ross, "static", str(case), "--json")
    assert out.returncode == 0, out.stderr
    headline = json.loads(out.stdout)
    assert headline["converged"] and headline["load_N"] == pytest.approx(20.0)


def test_a_rotor_command_without_ross_says_how_to_add_it(
    no_ross: dict[str, str], tmp_path: Path
) -> None:
    out = _run(no_ross, "rotor", str(ROTOR))
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1, out.stderr
    assert "the rotor command needs ROSS" in lines[0]
    assert "pip install 'foilbearing[ross]'" in lines[0]
    out = _run(no_ross, "study", str(ROTOR), "--out", str(tmp_path / "study"))
    assert out.returncode == 2
    assert out.stderr.strip().count("\n") == 0 and "the study of a rotor needs ROSS" in out.stderr
