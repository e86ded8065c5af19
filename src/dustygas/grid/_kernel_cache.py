"""Keep numba's on-disk cache of the grid kernels consistent with their sources.

numba caches each compiled function next to its source file and checks only the timestamp of
*that* file; a kernel inlines the functions it calls from other modules, so editing, say,
``riemann.py`` would leave a stale ``sweep_pencils`` in the cache. At import this module hashes
the sources of the package's kernel modules (those that use numba, and ``mesh.py`` whose
records the kernels receive) and, when the hash changed, removes the package's cache files
so that every kernel is recompiled once. It does nothing when the cache directory is
not the in-tree ``__pycache__`` (``NUMBA_CACHE_DIR`` set) or is not writable.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

_HERE = Path(__file__).resolve().parent


def ensure_fresh_cache(package_dir: Path = _HERE) -> bool:
    """Drop the package's numba cache files if any source changed; True if files were removed."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return False
    digest = hashlib.sha1()
    for src in sorted(package_dir.glob("*.py")):
        text = src.read_bytes()
        if b"numba" in text or src.name == "mesh.py":
            digest.update(src.name.encode())
            digest.update(text)
    stamp = digest.hexdigest()
    cache = package_dir / "__pycache__"
    marker = cache / "kernel-sources.sha1"
    try:
        if marker.read_text() == stamp:
            return False
    except OSError:
        pass
    removed = False
    try:
        cache.mkdir(exist_ok=True)
        for f in list(cache.glob("*.nbi")) + list(cache.glob("*.nbc")):
            f.unlink(missing_ok=True)
            removed = True
        tmp = marker.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(stamp)
        tmp.replace(marker)
    except OSError:  # read-only installation: numba uses its user-wide cache there
        return False
    return removed
