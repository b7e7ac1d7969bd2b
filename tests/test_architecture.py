"""The layout's rules, read from the source's imports (no module is run): the test oracles of
:mod:`foilbearing.testing` stay off the production path, and the modules import each other
without cycles. Every import counts: at module level, inside functions, and under
``TYPE_CHECKING`` (a type-only import back is still a loop a reader must untangle)."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
TESTING = "foilbearing.testing"


def module_name(path: Path) -> str:
    """Dotted name of a source file under ``SRC`` (a package is its ``__init__``)."""
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def source_modules() -> dict[str, Path]:
    """Every module of the ``foilbearing`` package, by dotted name."""
    return {module_name(p): p for p in sorted((SRC / "foilbearing").rglob("*.py"))}


def imported_names(path: Path, name: str) -> Iterator[tuple[str, int]]:
    """Each dotted name the file imports, with its line, at any depth of the file:
    ``import a.b`` gives ``a.b``; ``from a import b`` gives ``a.b`` (b may be a module or
    a name defined in a). Relative imports are resolved against the file's package."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, node.lineno
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            for alias in node.names:
                yield f"{base}.{alias.name}", node.lineno


def import_graph() -> dict[str, set[str]]:
    """module → the source modules it imports: ``from a import b`` is an arrow to the module
    a.b if there is one, else to a (b a name defined in a); importing a submodule runs its
    package's ``__init__`` too, which is not drawn (as for every submodule import)."""
    modules = source_modules()
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        targets = set()
        for target, _line in imported_names(path, name):
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target:
                targets.add(target)
        graph[name] = targets - {name}
    return graph


def import_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(cycles)


def test_production_never_imports_the_test_oracles() -> None:
    """No module of foilbearing outside foilbearing.testing imports it, at any level."""
    offenders = [
        f"{path.relative_to(SRC)}:{line} imports {target}"
        for name, path in source_modules().items()
        if name != TESTING and not name.startswith(TESTING + ".")
        for target, line in imported_names(path, name)
        if target == TESTING or target.startswith(TESTING + ".")
    ]
    assert not offenders, "; ".join(offenders)


#: The generic integrator and what it may import of the package: nothing (numpy and numba
#: are not the package's). Every other package of foilbearing is a bearing package.
INTEGRATE = "foilbearing.integrate"


def test_the_integrator_imports_nothing_of_the_bearing_packages() -> None:
    """foilbearing.integrate knows nothing of the problem: none of its modules imports
    another module of foilbearing outside it, at any level."""
    modules = source_modules()
    inside = [name for name in modules if name == INTEGRATE or name.startswith(INTEGRATE + ".")]
    assert len(inside) >= 4  # the package is there: the check below reads its files
    offenders = [
        f"{modules[name].relative_to(SRC)}:{line} imports {target}"
        for name in inside
        for target, line in imported_names(modules[name], name)
        if target.split(".")[0] == "foilbearing"
        and not (target == INTEGRATE or target.startswith(INTEGRATE + "."))
    ]
    assert not offenders, "; ".join(offenders)


def test_the_source_modules_import_without_cycles() -> None:
    cycles = import_cycles(import_graph())
    assert not cycles, " | ".join(" <-> ".join(c) for c in cycles)


def test_the_checks_see_every_kind_of_import(tmp_path: Path) -> None:
    """The checks above can fail: a loop through three modules is found, and a type-only,
    a function-level and a relative import are each read as an arrow."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert import_cycles(graph) == [["a", "b", "c"]]
    path = tmp_path / "m.py"
    path.write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n    from foilbearing.x import Y\n"
        "def f():\n    import foilbearing.testing.twins\n"
        "from . import sibling\n",
        encoding="utf-8",
    )
    found = {target for target, _line in imported_names(path, "foilbearing.pkg.m")}
    assert found >= {"foilbearing.x.Y", "foilbearing.testing.twins", "foilbearing.pkg.sibling"}


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("foilbearing.reynolds.reference", "foilbearing.testing.twins"),
        ("foilbearing.orbit.reference", "foilbearing.testing.ivp_orbit"),
    ],
)
def test_an_old_oracle_path_names_its_new_home(old: str, new: str) -> None:
    """``from <old> import X`` fails in one line that names where X lives now."""
    import importlib
    import re

    module = importlib.import_module(old)
    name = sorted(module.MOVED)[0]
    with pytest.raises(
        ImportError, match=re.escape(f"{old}.{name} has moved to {module.MOVED[name]}")
    ):
        getattr(module, name)
    assert any(home.startswith(new) for home in module.MOVED.values())


def test_the_rotor_s_moved_solve_ivp_methods_name_their_new_home() -> None:
    from foilbearing.rotor.nonlinear import RotorOrbitSystem

    system = object.__new__(RotorOrbitSystem)  # the message needs no built system
    with pytest.raises(AttributeError, match=r"foilbearing\.testing\.ivp_rotor\.RotorIVP"):
        system.run(0.01)
    with pytest.raises(AttributeError, match="no attribute 'runn'"):
        system.runn  # noqa: B018
