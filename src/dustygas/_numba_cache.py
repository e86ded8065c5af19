"""Keep numba's on-disk cache of every dustygas kernel consistent with all the sources it inlines.

numba caches a compiled function (``@njit(cache=True)``) keyed by a hash of the file that
defines it, but a kernel inlines the functions it calls from *other* modules: editing
``sph/kernels.py`` would leave the cached density solver running the old kernel. At
``import dustygas`` this module puts one cache locator in front of numba's own, for functions
defined inside the dustygas package only:

* its **source stamp** is a SHA-256 over the function's file and every dustygas module that
  file imports, transitively (lazy imports inside functions count too): an edit of any module the kernel can inline changes the stamp and the
  kernel is compiled afresh;
* the stamp is also part of the cache **file names**: index and data files of different source
  versions never share a name, so a process running the old sources and one running the new
  (two checkouts sharing ``NUMBA_CACHE_DIR``, an edit while a run is going) never read each
  other's files, and nothing is ever deleted. Two processes compiling or loading at once cannot
  break each other: numba writes each file under a unique temporary name and renames it.

A data file that cannot be read back (damaged on disk, truncated by a copy taken mid-write,
edited by a tool that took it for text) is not fatal: the kernel is compiled afresh with a
warning naming it, and the new file replaces the damaged one.

The cache directory is numba's usual choice (``NUMBA_CACHE_DIR``, else the in-tree
``__pycache__``, else the user-wide cache). Files of source versions that no longer exist stay
there (a few MB per version) until ``__pycache__`` is cleared.
"""

from __future__ import annotations

import functools
import hashlib
import re
import warnings
from pathlib import Path

__all__ = ["install", "load_for_arguments", "source_stamp"]

_ROOT = Path(__file__).resolve().parent
_PACKAGE = _ROOT.name


def _module_file(name: str) -> Path | None:
    """File of the dustygas module or package ``name`` (``dustygas.sph.kernels``), if any."""
    parts = name.split(".")
    if not parts or parts[0] != _PACKAGE:
        return None
    base = _ROOT.joinpath(*parts[1:])
    candidates = ([base.with_suffix(".py")] if len(parts) > 1 else []) + [base / "__init__.py"]
    return next((c for c in candidates if c.is_file()), None)


def _package_of(path: Path) -> list[str]:
    rel = path.relative_to(_ROOT).with_suffix("")
    parts = [_PACKAGE, *rel.parts]
    return parts[:-1]  # for __init__.py the package itself, for a module its package


_FROM_IMPORT = re.compile(r"^[ \t]*from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#;]*)", re.M)
_IMPORT = re.compile(r"^[ \t]*import[ \t]+([\w. \t,]+)", re.M)


@functools.lru_cache(maxsize=None)
def _direct_imports(path: Path) -> tuple[Path, ...]:
    """dustygas files imported anywhere in ``path`` (``import x``, ``from .a import b``).

    A regular expression over the text, not a parse: an import quoted in a docstring also
    counts, which can only cause an unneeded recompilation, never a stale kernel.
    """
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ()
    package = _package_of(path)
    names: list[str] = []
    for dots, module, imported in _FROM_IMPORT.findall(text):
        if dots:
            base = package[: len(package) - (len(dots) - 1)]
            module = ".".join(base + ([module] if module else []))
        names.append(module)
        for item in imported.strip("() \t\n").split(","):
            item = item.split()[0] if item.split() else ""
            if item.isidentifier():
                names.append(f"{module}.{item}")  # the imported name may be a module
    for group in _IMPORT.findall(text):
        names.extend(item.split()[0] for item in group.split(",") if item.split())
    found = {file for name in names if (file := _module_file(name)) is not None}
    return tuple(sorted(found))


@functools.lru_cache(maxsize=None)
def source_stamp(path: Path) -> str:
    """SHA-256 (hex) of ``path`` and of every dustygas module it imports, transitively."""
    seen: set[Path] = set()
    todo = [Path(path).resolve()]
    while todo:
        file = todo.pop()
        if file in seen:
            continue
        seen.add(file)
        todo.extend(_direct_imports(file))
    digest = hashlib.sha256()
    for file in sorted(seen):
        digest.update(str(file.relative_to(_ROOT)).encode())
        digest.update(_file_digest(file))
    return digest.hexdigest()


@functools.lru_cache(maxsize=None)
def _file_digest(path: Path) -> bytes:
    try:
        return hashlib.sha256(path.read_bytes()).digest()
    except OSError:
        return b"<unreadable>"


def _locator_class():
    from numba.core import caching

    class DependencyStampLocator(caching._CacheLocator):
        """numba's locator for the directory; a stamp over the kernel's whole import closure."""

        def __init__(self, inner, py_file: Path):
            self._inner = inner
            self._py_file = str(py_file)  # numba's warning for a kernel it cannot cache reads it
            self._stamp = source_stamp(py_file)

        def ensure_cache_path(self) -> None:
            self._inner.ensure_cache_path()

        def get_cache_path(self) -> str:
            return self._inner.get_cache_path()

        def get_source_stamp(self) -> str:
            return self._stamp

        def get_disambiguator(self) -> str:
            return f"{self._inner.get_disambiguator()}-{self._stamp[:16]}"

        @classmethod
        def from_function(cls, py_func, py_file):
            try:
                path = Path(py_file).resolve()
            except (OSError, RuntimeError, TypeError):
                return None
            if _ROOT not in path.parents or not path.is_file():
                return None
            for other in caching.CacheImpl._locator_classes:
                if getattr(other, "_dustygas_locator", False):
                    continue
                inner = other.from_function(py_func, py_file)
                if inner is not None:
                    return cls(inner, path)
            return None

    DependencyStampLocator._dustygas_locator = True
    return DependencyStampLocator


def _tolerant_load(original):
    """numba's ``Cache.load_overload`` that compiles afresh, with a warning, when a dustygas
    kernel's cached data cannot be read back (any other cache behaves as before)."""

    def load_overload(self, sig, target_context):
        try:
            return original(self, sig, target_context)
        except Exception as exc:
            if not getattr(self._impl.locator, "_dustygas_locator", False):
                raise
            warnings.warn(f"dustygas: the cached compiled code of {self._name} could not be read "
                          f"({type(exc).__name__}: {exc}); compiling it afresh", RuntimeWarning, stacklevel=2)
            return None

    load_overload._dustygas_tolerant = True
    return load_overload


def install() -> None:
    """Put the dustygas locator first in numba's list and make a damaged cache file of a dustygas
    kernel a recompilation instead of an error (idempotent)."""
    from numba.core import caching

    if not getattr(caching.Cache.load_overload, "_dustygas_tolerant", False):
        caching.Cache.load_overload = _tolerant_load(caching.Cache.load_overload)
    classes = caching.CacheImpl._locator_classes
    if any(getattr(c, "_dustygas_root", None) == _ROOT for c in classes):
        return
    locator = _locator_class()
    locator._dustygas_root = _ROOT  # each copy of dustygas answers for its own files only
    classes.insert(0, locator)


def load_for_arguments(kernel, args: tuple) -> None:
    """Have numba load ``kernel`` from this cache (or compile it) for the types of ``args``,
    without running it: the overload a later ``kernel(*args)`` finds ready.

    The types are numba's own for a call (``typeof_pyval``), so a call with values of the same
    types dispatches to this overload; the engines' ``load_kernels()`` use it before the run
    loop's clock starts (:mod:`dustygas.runner`).
    """
    kernel.compile(tuple(kernel.typeof_pyval(a) for a in args))
