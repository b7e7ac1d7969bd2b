"""The layout's rules, read from the source (no module is run): the test oracles of
:mod:`foilbearing.testing` stay off the production path, and the modules import each other
without cycles. Every import counts: at module level, inside functions, and under
``TYPE_CHECKING`` (a type-only import back is still a loop a reader must untangle). No module
of ``src/`` or ``benchmarks/`` exceeds 600 lines, and each package's docstring carries its
module → responsibility table, the same as docs/development/architecture.md's."""

from __future__ import annotations

import ast
import re
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
TESTING = "foilbearing.testing"

#: The longest a module of src/ or benchmarks/ may be, in lines.
MAX_LINES = 600
#: Modules over MAX_LINES that are being split: each entry says by whom. Shrink it as they are.
OVER_MAX_LINES = {
    "src/foilbearing/output/report/sections.py": "the report's sections, split with the report",
    "src/foilbearing/rotor/stepper.py": "the rotor's stepper, split with the rotor's Newton",
}
#: Packages whose docstring does not carry its table yet, and why.
NO_TABLE_YET = {
    "foilbearing.output.report": "the report package is being reorganised",
    "foilbearing.integrate": "the generic BDF integrator, being built (issue 46, item 4)",
}


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


def test_no_module_is_over_600_lines() -> None:
    """A long module is one that holds more than one responsibility: split it by them."""
    files = sorted([*(SRC / "foilbearing").rglob("*.py"), *(ROOT / "benchmarks").glob("*.py")])
    long = {
        str(f.relative_to(ROOT)): n
        for f in files
        if (n := len(f.read_text(encoding="utf-8").splitlines())) > MAX_LINES
    }
    over = [f"{f}: {n} lines" for f, n in long.items() if f not in OVER_MAX_LINES]
    assert not over, f"over {MAX_LINES} lines: " + "; ".join(over)
    gone = [f for f in OVER_MAX_LINES if not (ROOT / f).exists()]
    assert not gone, f"OVER_MAX_LINES names files that are gone: {gone}"


def _markup_free(text: str) -> str:
    """A table cell as words: code marks and runs of whitespace made uniform."""
    return " ".join(text.replace("``", "`").split())


def docstring_table(docstring: str) -> dict[str, str]:
    """The rows of the ``module  responsibility`` table (an RST simple table) of a docstring:
    module → responsibility, continuation lines joined; empty if it has none."""
    lines = docstring.splitlines()
    rows: dict[str, str] = {}
    for i in range(len(lines) - 2):
        if lines[i].startswith("==") and re.match(r"module\s+responsibility$", lines[i + 1]):
            width = len(lines[i].split()[0]) + 2
            last = ""
            for line in lines[i + 3 :]:
                if line.startswith("=="):
                    return {k: _markup_free(v) for k, v in rows.items()}
                name, text = line[:width].strip(), line[width:]
                if name:
                    last = name.strip("`")
                    rows[last] = text
                else:
                    rows[last] += " " + text
    return {k: _markup_free(v) for k, v in rows.items()}


def markdown_tables(text: str) -> dict[str, dict[str, str]]:
    """The tables of docs/development/architecture.md's "Packages" section: package → module → responsibility."""
    section = text.split("## Packages", 1)[1].split("\n## ", 1)[0]
    tables: dict[str, dict[str, str]] = {}
    for block in section.split("\n### ")[1:]:
        package = block.split("\n", 1)[0].strip().strip("`")
        rows = re.findall(r"^\| `([^`]+)` \| (.*) \|$", block, flags=re.M)
        tables[package] = {name: _markup_free(cell) for name, cell in rows}
    return tables


def package_entries(directory: Path) -> set[str]:
    """The modules (stems) and subpackages (``name/``) of a package directory."""
    modules = {p.stem for p in directory.glob("*.py") if p.name != "__init__.py"}
    return modules | {d.name + "/" for d in directory.iterdir() if (d / "__init__.py").exists()}


def packages() -> dict[str, Path]:
    """Every package of ``foilbearing`` by dotted name, with its directory."""
    return {module_name(p): p.parent for p in sorted((SRC / "foilbearing").rglob("__init__.py"))}


@pytest.mark.parametrize("package", sorted(set(packages()) - set(NO_TABLE_YET)))
def test_a_package_docstring_tables_its_modules_as_the_architecture_does(package: str) -> None:
    directory = packages()[package]
    doc = ast.get_docstring(ast.parse((directory / "__init__.py").read_text(encoding="utf-8")))
    table = docstring_table(doc or "")
    entries = package_entries(directory)
    assert set(table) == entries, (
        f"{package}'s docstring table: missing {sorted(entries - set(table))}, "
        f"not a module {sorted(set(table) - entries)}"
    )
    docs = markdown_tables(
        (ROOT / "docs" / "development" / "architecture.md").read_text(encoding="utf-8")
    )
    assert docs.get(package) == table, (
        f"docs/development/architecture.md's table of {package} differs"
    )


def test_the_table_readers_see_a_missing_module_and_a_changed_row(tmp_path: Path) -> None:
    """The check above can fail: a docstring table is read with its continuation lines, a
    module missing from it shows, and a row that differs from the document's shows."""
    doc = (
        "Words.\n\n"
        "==========  =====\n"
        "module      responsibility\n"
        "==========  =====\n"
        "``a``       first line\n"
        "            and its continuation\n"
        "``sub/``    a subpackage\n"
        "==========  =====\n"
    )
    table = docstring_table(doc)
    assert table == {"a": "first line and its continuation", "sub/": "a subpackage"}
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "__init__.py").write_text("")
    for name in ("__init__.py", "a.py", "b.py"):
        (tmp_path / name).write_text("")
    assert package_entries(tmp_path) - set(table) == {"b"}
    md = (
        "## Packages\n\n### `p`\n\n| module | responsibility |\n|---|---|\n"
        "| `a` | first line and its `continuation` |\n| `sub/` | a subpackage |\n\n## Next\n"
    )
    assert markdown_tables(md) == {
        "p": {"a": "first line and its `continuation`", "sub/": "a subpackage"}
    }
    assert markdown_tables(md)["p"] != table  # one code mark apart


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("foilbearing.static", "foilbearing.analysis.equilibrium"),
        ("foilbearing.coefficients", "foilbearing.analysis.coefficients"),
        ("foilbearing.stability", "foilbearing.analysis.stability"),
    ],
)
def test_an_analysis_s_old_module_name_is_its_new_module(old: str, new: str) -> None:
    """Code that imports an analysis from its old module, or patches a name there, reaches
    the module that runs: the old name is the same module object, not a copy of its names."""
    import importlib

    old_module, new_module = importlib.import_module(old), importlib.import_module(new)
    assert old_module is new_module
    assert set(new_module.__all__) <= set(vars(old_module))


#: The modules moved into the ``control`` and ``design`` packages: old name → new module.
MOVED_MODULES = [
    ("foilbearing.schedule_file", "foilbearing.control.schedule_file"),
    ("foilbearing.optimize", "foilbearing.design.voltages"),
    ("foilbearing.schedule", "foilbearing.design.schedule_search"),
]


@pytest.mark.parametrize(("old", "new"), MOVED_MODULES)
def test_a_moved_module_s_old_name_is_its_new_module(old: str, new: str) -> None:
    """The modules gathered into the control and design packages answer under their old
    names: the old name is the same module object, so an import or a patch reaches it."""
    import importlib

    old_module, new_module = importlib.import_module(old), importlib.import_module(new)
    assert old_module is new_module
    assert set(new_module.__all__) <= set(vars(old_module))


def test_the_control_package_exports_what_the_control_module_did() -> None:
    """``foilbearing.control`` was one module; as a package it hands on every name it had."""
    import foilbearing.control as control

    before = {
        "SpeedProfile",
        "SubsyncController",
        "VoltageProgram",
        "VoltageSchedule",
        "constant_speed",
        "linear_ramp",
        "voltage_ramp",
    }
    assert set(control.__all__) == before
    assert all(callable(getattr(control, name)) for name in before)


def test_the_design_package_exports_what_the_design_module_did() -> None:
    """``foilbearing.design`` was the stack-stiffness module; as a package it hands on its
    names, the same objects as those of its new module."""
    import foilbearing.design as design
    from foilbearing.design import stack

    assert set(design.__all__) == {"READINGS", "StackDesign", "stack_design"}
    assert all(getattr(design, name) is getattr(stack, name) for name in design.__all__)
