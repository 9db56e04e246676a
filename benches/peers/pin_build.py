"""Build a C++ harness against Pinocchio, for the peer scripts (compare.py, chains.py).

The harnesses (pinocchio_call.cpp, pinocchio_chain.cpp) time Pinocchio's C++ calls with no Python
between the clock and the call.  They are compiled with g++ against the headers and libraries the
`pin` wheel installs (its cmeel prefix, found on this interpreter's sys.path) and Eigen's headers
(`cmeel-eigen`), with the compile definitions Pinocchio's CMake package exports, into a cache
directory (``$CARGO_TARGET_DIR/peers/`` by the callers), and rebuilt when the source is newer.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

PIN_DEFINES = ["-DBOOST_MPL_LIMIT_LIST_SIZE=30", "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
               "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS", "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
               "-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION"]


def cmeel_prefix() -> Path | None:
    for entry in sys.path:
        prefix = Path(entry) / "cmeel.prefix"
        if (prefix / "include" / "pinocchio").is_dir():
            return prefix
    return None


def unavailable() -> str | None:
    """Why no harness can be built here (no cmeel prefix, no Eigen headers, no g++), or None."""
    prefix = cmeel_prefix()
    if prefix is None:
        return "no cmeel prefix with Pinocchio's headers on sys.path (pip install pin)"
    if not (prefix / "include" / "eigen3" / "Eigen").is_dir():
        return "no Eigen headers in the cmeel prefix (pip install cmeel-eigen)"
    if shutil.which("g++") is None:
        return "no g++ on PATH"
    return None


def pinocchio_binary(src: Path, cache: Path, libs: tuple = ()):
    """The compiled `src` in `cache` (named after it), or (None, reason).  Rebuilt when the source
    is newer.  `libs`: more libraries of the cmeel prefix to link (e.g. "boost_serialization")."""
    why = unavailable()
    if why:
        return None, why
    prefix = cmeel_prefix()
    out = cache / src.stem
    if out.exists() and out.stat().st_mtime >= src.stat().st_mtime:
        return out, None
    cache.mkdir(parents=True, exist_ok=True)
    cmd = ["g++", "-O3", "-DNDEBUG", "-std=c++17", *PIN_DEFINES, f"-I{prefix / 'include'}",
           f"-I{prefix / 'include' / 'eigen3'}", str(src), f"-L{prefix / 'lib'}", "-lpinocchio_default",
           *(f"-l{lib}" for lib in libs), f"-Wl,-rpath,{prefix / 'lib'}", "-o", str(out)]
    print(f"  building {out.name} (g++ against Pinocchio's headers; a minute or two) ...", flush=True)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        errs = [l for l in p.stderr.splitlines() if "error" in l]
        return None, f"g++ failed: {errs[0] if errs else p.stderr[-300:]}"
    return out, None
