"""The layering, read from the source: the core is a leaf and nothing imports in a circle.

Every import counts, also one inside a function: a lazy import is still a dependency, and a
cycle hidden in a function is still a cycle. Modules are the project's own (`events`, `apps`,
`sentinel_site`, `sentinel_environments`, `tests`); a package is one of those or one
`apps.<name>`.
"""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
OWN = ("events", "apps", "sentinel_site", "sentinel_environments", "tests")


def module_name(path: Path) -> str:
    parts = path.relative_to(REPO).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def project_modules() -> dict[str, Path]:
    return {
        module_name(path): path
        for top in OWN
        for path in (REPO / top).rglob("*.py")
        if "migrations" not in path.parts
    }


def imported_names(path: Path, module: str) -> set[str]:
    """Every module name `path` imports, anywhere in the file (relative imports resolved)."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names)  # submodules
    return names


def module_graph() -> dict[str, set[str]]:
    modules = project_modules()
    graph: dict[str, set[str]] = defaultdict(set)
    for module, path in modules.items():
        for name in imported_names(path, module):
            if name in modules and name != module:
                graph[module].add(name)
    return graph


def package_of(module: str) -> str:
    parts = module.split(".")
    return ".".join(parts[:2]) if parts[0] == "apps" and len(parts) > 1 else parts[0]


def package_graph(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    packages: dict[str, set[str]] = defaultdict(set)
    for module, targets in graph.items():
        for target in targets:
            if package_of(target) != package_of(module):
                packages[package_of(module)].add(package_of(target))
    return packages


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one member (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in graph.get(node, ()):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(set(graph) | {t for targets in graph.values() for t in targets}):
        if node not in index:
            visit(node)
    return found


def test_the_core_imports_nothing_from_apps_or_tests():
    graph = module_graph()
    upward = sorted(
        f"{module} imports {target}"
        for module, targets in graph.items()
        if package_of(module) == "events"
        for target in targets
        if package_of(target) != "events"
    )
    assert upward == []


# The engine is only the engine: pages, URLs and sockets are the site's (apps.kit), never its own.
SITE_LIBRARIES = ("django.http", "django.urls", "django.shortcuts", "django.template", "channels")


def site_imports(module: str, names: set[str]) -> list[str]:
    return sorted(
        f"{module} imports {name}"
        for name in names
        if any(name == lib or name.startswith(lib + ".") for lib in (*SITE_LIBRARIES, "apps"))
    )


def test_the_engine_imports_no_web_library_and_no_app():
    modules = project_modules()
    found = [
        line
        for module, path in modules.items()
        if package_of(module) == "events"
        for line in site_imports(module, imported_names(path, module))
    ]
    assert found == []


def test_the_engine_rule_catches_a_web_import():
    assert site_imports("events.x", {"django.http.response", "django.db", "apps.kit.live"}) == [
        "events.x imports apps.kit.live",
        "events.x imports django.http.response",
    ]


def test_no_module_imports_itself_through_others():
    assert cycles(module_graph()) == []


def test_no_package_imports_itself_through_others():
    assert cycles(package_graph(module_graph())) == []


def test_the_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(graph) == [["a", "b", "c"]]


# --- one environment shape ---------------------------------------------------------------------

ENVIRONMENT_MODULES = (
    "state",  # the immutable state and the questions asked of it
    "catalog",  # catalog records → items
    "actions",  # the agent's actions
    "environment",  # its Environment: scenario events, baselines, evaluation tables
    "query",  # URL state of its screens
    "screens",  # what each screen shows, from the state
    "views",  # thin views
    "urls",
    "bench",  # sample pages for bench_pages
)
TEST_ONLY = {"tally"}  # an environment the tests install, without catalog or pages to speak of


def environment_apps() -> list[Path]:
    return sorted(
        path.parent
        for path in (REPO / "apps").glob("*/environment.py")
        if path.parent.name not in TEST_ONLY
    )


def shape_problems(app: Path) -> list[str]:
    name = app.name
    problems = [
        f"{name}: no {module}.py"
        for module in ENVIRONMENT_MODULES
        if not (app / f"{module}.py").is_file()
    ]
    if (app / "apps.py").is_file():
        problems.append(f"{name}: apps.py (the kit finds environment apps: apps.kit.environments)")
    for needed in (
        "README.md",
        f"templates/{name}/base.html",
        f"static/{name}/{name}.css",
        f"static/{name}/favicon.svg",
    ):
        if not (app / needed).is_file():
            problems.append(f"{name}: no {needed}")
    for template in (app / "templates").rglob("*.html"):
        text = template.read_text(encoding="utf-8")
        if "<style" in text:
            problems.append(
                f"{name}: inline styles in {template.relative_to(app)} (use static/{name}/{name}.css)"
            )
        if "toast" in text:
            problems.append(
                f"{name}: {template.relative_to(app)} renders toasts (the shared base does)"
            )
    for script in (app / "static" / name).glob("*.js"):
        if script.name != f"{name}.js":
            problems.append(f"{name}: script {script.name} (one script per environment: {name}.js)")
    tree = ast.parse((app / "environment.py").read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef) and node.name.startswith("reduce_new_"):
            problems.append(
                f"{name}: hand-written arrival reducer {node.name} (apps.kit.arrivals.arrival)"
            )
        if isinstance(node, ast.ClassDef) and node.name.startswith("New"):
            problems.append(
                f"{name}: hand-written arrival payload {node.name} (apps.kit.arrivals.arrival)"
            )
    for module in app.rglob("*.py"):
        source = module.read_text(encoding="utf-8")
        if "CREATE TABLE" in source:
            problems.append(
                f"{name}: {module.relative_to(app)} writes tables by hand (apps.kit.tables)"
            )
    return problems


def test_every_environment_has_the_same_shape():
    apps = environment_apps()
    assert len(apps) >= 10
    assert [problem for app in apps for problem in shape_problems(app)] == []


def test_the_shape_check_names_what_is_missing(tmp_path):
    app = tmp_path / "microbroken"
    (app / "templates" / "microbroken").mkdir(parents=True)
    (app / "environment.py").write_text("def reduce_new_thing(state, event):\n    return state\n")
    (app / "templates" / "microbroken" / "page.html").write_text("<style>p{}</style>")
    (app / "apps.py").write_text("")
    problems = shape_problems(app)
    assert (
        "microbroken: apps.py (the kit finds environment apps: apps.kit.environments)" in problems
    )
    assert "microbroken: no screens.py" in problems
    assert "microbroken: no static/microbroken/microbroken.css" in problems
    assert any("inline styles in templates/microbroken/page.html" in p for p in problems)
    assert any("hand-written arrival reducer reduce_new_thing" in p for p in problems)
