"""Every import points down the layers (docs/design.md section 2; issue 21).

Each module of ``kernels`` and ``sweep`` is read with ``ast`` (nothing is imported), and every
import statement in it, at module level or inside a function, absolute or relative, is
resolved to the module it names: ``from .. import cf`` in ``sweep.runner.store`` names
``sweep.cf``; ``from .. import __version__`` names the package ``sweep`` itself.  Each module
belongs to a layer of ``LAYERS``, bottom to top; a module may import its own layer (``paper``
and ``probability`` are one layer, the commands another) and the layers below it, never one
above.  ``kernels`` never imports ``sweep``, mpi4py, xarray or matplotlib either.  A module that
no layer names fails the test too: a new module is placed in a layer when it is added.  No
two modules import each other, directly or round a circle (lazy imports inside functions
included), and one module, ``kernels.gpu``, is the door to the GPU: the only one that imports
``kernels.cuda_batch``.

The bottom of ``sweep`` is ``sweep._version`` and ``sweep.bodies`` (g and the body scales);
``sweep.cf``, the one CF metadata table, sits below the runner that fills it.  Two modules are
placed by what they are rather than by their folder:

* ``sweep`` itself (``sweep/__init__.py``) is the public API, the top layer: it may import
  anything (``sweep.simulate`` and ``sweep.run_study`` call the runner), and nothing may import
  it (``from sweep import __version__`` is an import of the top layer: the version lives in
  ``sweep._version``).  Importing a submodule runs the ``__init__`` of its packages; that is not
  counted, only what an import statement names.
* ``sweep.cli`` is the plumbing every command shares (argument parser, how a command ends, JSON
  printing, ``report_command``; the exit statuses themselves are ``sweep.io.exits``, the one
  table that commands and the runner alike import).  It imports only ``io``, and the report modules of ``paper``
  (``python -m sweep.paper.rates``, ``python -m sweep.paper.subharmonic``) and the runner's
  ``runner.command`` (the arguments of ``python -m sweep.run``) build their ``main`` with it, so
  it sits just above ``io``, below everything that may call it.  The thin command modules
  (``sweep.run``, ``sweep.scene``, ...) are the layer under the public API.
"""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("kernels", "sweep")

# Bottom to top: (label, modules and packages); a module belongs to the layer of the longest
# name that is it or one of its packages.
LAYERS = (
    ("kernels", ("kernels",)),  # numba physics
    ("bottom", ("sweep._version", "sweep.bodies")),  # the version; g and the body scales
    ("groundmotion", ("sweep.groundmotion",)),  # motions as numbers
    ("io", ("sweep.io",)),  # files, units, schemas, record formats, the study's vocabulary
    ("cli", ("sweep.cli",)),  # what every command shares (see above)
    ("cf", ("sweep.cf", "sweep.netcdf")),  # the one CF metadata table, its netCDF writer
    ("runner", ("sweep.runner",)),  # grid, cells, MPI, store, refine, lock, fingerprint, ...
    ("paper and probability", ("sweep.paper", "sweep.probability")),
    ("plots", ("sweep.plots",)),  # figures from datasets
    ("commands", ("sweep.run", "sweep.scene", "sweep.plot", "sweep.fragility", "sweep.estimate",
                  "sweep.figures", "sweep.risk")),  # the thin python -m commands
    ("public API", ("sweep",)),  # sweep/__init__.py
)
KERNEL_FORBIDDEN = ("sweep", "mpi4py", "xarray", "matplotlib")


def _modules():
    """{dotted module name: path} of every module of the packages."""
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            found[".".join(parts)] = path
    return found


MODULES = _modules()


def _is_package(name):
    return MODULES.get(name) is not None and MODULES[name].name == "__init__.py"


def layer(name):
    """Index in ``LAYERS`` of a module of ``kernels`` or ``sweep``, or None when none names it."""
    best, rank = -1, None
    for i, (_, names) in enumerate(LAYERS):
        for prefix in names:
            if (name == prefix or name.startswith(prefix + ".")) and len(prefix) > best:
                best, rank = len(prefix), i
    return rank


def imports(name, path):
    """``(line, text, imported module)`` of every import in a module, functions included."""
    tree = ast.parse(path.read_text(), filename=str(path))
    package = name if _is_package(name) else name.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, f"import {alias.name}", alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1])
                source = f"{base}.{node.module}" if node.module else base
            else:
                source = node.module
            text = f"from {'.' * node.level}{node.module or ''} import "
            for alias in node.names:
                # ``from pkg import mod`` names the submodule; ``from pkg import x`` the package
                target = f"{source}.{alias.name}"
                yield node.lineno, text + alias.name, target if target in MODULES else source


def upward_imports():
    """Every import that points up the layers: ``path:line: import (layer -> higher layer)``."""
    found = []
    for name, path in MODULES.items():
        here = layer(name)
        where = path.relative_to(ROOT)
        for line, text, target in sorted(imports(name, path)):
            top = target.split(".")[0]
            if name.split(".")[0] == "kernels" and top in KERNEL_FORBIDDEN:
                found.append(f"{where}:{line}: {text} (kernels never imports {top})")
            elif top in PACKAGES and here is not None:
                there = layer(target)
                if there is not None and there > here:
                    found.append(f"{where}:{line}: {text} ({LAYERS[here][0]} imports "
                                 f"{target}, of the higher layer {LAYERS[there][0]})")
    return found


def import_graph():
    """{module: sorted modules of the packages it imports}, functions included."""
    return {name: sorted({target for _, _, target in imports(name, path)
                          if target in MODULES and target != name})
            for name, path in MODULES.items()}


def circles(graph):
    """Every import circle a depth-first walk of ``graph`` meets, each as the path of modules
    back to where it starts."""
    found, state = [], {}

    def visit(name, path):
        state[name] = "open"
        for target in graph[name]:
            if state.get(target) == "open":
                found.append(path[path.index(target):] + [target])
            elif target not in state:
                visit(target, path + [target])
        state[name] = "done"

    for name in graph:
        if name not in state:
            visit(name, [name])
    return found


def test_every_module_has_a_layer():
    assert [name for name in MODULES if layer(name) is None] == []


def test_every_import_points_down_the_layers():
    found = upward_imports()
    assert not found, "imports of a higher layer:\n" + "\n".join(found)


def test_an_upward_import_is_found(tmp_path):
    """The walk sees relative, absolute and function-level imports of a higher layer."""
    source = ("from ..paper import criteria\n"
              "import sweep.runner.grid\n"
              "def f():\n"
              "    from .. import __version__\n")
    path = tmp_path / "units.py"
    path.write_text(source)
    found = [(line, target) for line, _, target in imports("sweep.io.units", path)]
    assert found == [(1, "sweep.paper.criteria"), (2, "sweep.runner.grid"), (4, "sweep")]
    assert [layer(target) > layer("sweep.io.units") for _, target in found] == [True] * 3


def test_no_import_circle():
    assert circles(import_graph()) == []


def test_an_import_circle_is_found():
    graph = {"a": ["b"], "b": ["c"], "c": ["a"], "d": ["a", "e"], "e": []}
    assert circles(graph) == [["a", "b", "c", "a"]]


def test_one_door_to_the_gpu():
    """Only ``kernels.gpu`` imports ``kernels.cuda_batch`` (numba-cuda)."""
    assert [name for name, targets in import_graph().items()
            if "kernels.cuda_batch" in targets] == ["kernels.gpu"]
