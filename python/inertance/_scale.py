"""Scale-out: ``solve_batch`` and ``sweep`` over an executor (guide/python.md, "Scale-out").

The points are split into contiguous chunks, one task per chunk is submitted to the executor
(anything with ``submit(fn, *args)`` returning an object with ``result()``:
``concurrent.futures`` pools, Dask's ``client.get_executor()``, submitit's executors), and the
chunks' results are joined in point order. A task carries the
scene's TOML text, never the native :class:`Scene` (which does not pickle), so it runs on any
worker with ``inertance`` installed, whether or not it sees the caller's files.

A sweep's chunks are the CLI's shards: chunk i of n solves exactly the global points that
``inertance sweep --shard i/n`` solves, ``[⌊(i−1)·P/n⌋, ⌊i·P/n⌋)``, with their global
``point`` index, so joining them gives the in-process sweep's columns bit for bit. A batch's
chunks are the same blocks of its arrays.
"""

from __future__ import annotations

import math
import operator
import os
from typing import Any, Callable, Optional, Sequence

import numpy as np

from . import _inertance as _native
from ._inertance import Scene

# Chunks per worker by default: a few, so that a slow chunk does not leave the others idle.
CHUNKS_PER_WORKER = 4


def workers(executor: Any) -> int:
    """How many tasks ``executor`` runs at once, as far as it says: ``_max_workers`` of a
    ``concurrent.futures`` pool, the threads of a Dask client's workers; otherwise this
    machine's CPU count."""
    n = getattr(executor, "_max_workers", None)
    if isinstance(n, int) and n > 0:
        return n
    client = getattr(executor, "_client", None)
    nthreads = getattr(client, "nthreads", None)
    if callable(nthreads):
        total = sum(nthreads().values())
        if total > 0:
            return total
    return os.cpu_count() or 1


def chunk_count(executor: Any, points: int, chunk: Optional[int]) -> int:
    """How many chunks ``points`` points are split into: ``⌈points / chunk⌉`` (each at most
    ``chunk`` points), or by default ``CHUNKS_PER_WORKER`` per worker of ``executor`` (never
    more than the points)."""
    if chunk is None:
        return max(1, min(points, CHUNKS_PER_WORKER * workers(executor)))
    if isinstance(chunk, bool):
        raise TypeError("chunk= is a number of points per task, not a bool")
    chunk = operator.index(chunk)
    if chunk < 1:
        raise ValueError(f"chunk={chunk}: a chunk is at least 1 point (the most points per task)")
    return max(1, -(-points // chunk))


def block(i: int, n: int, points: int) -> tuple[int, int]:
    """Chunk ``i`` (from 1) of ``n`` over ``points`` points: ``[⌊(i−1)·P/n⌋, ⌊i·P/n⌋)``, the
    points of the CLI's ``--shard i/n``."""
    return (i - 1) * points // n, i * points // n


def gather(executor: Any, fn: Callable, calls: Sequence[tuple]) -> list:
    """``fn(*args)`` for every ``args`` of ``calls`` on ``executor``, the results in order.

    A submitit executor gets every task inside its ``batch()`` block, i.e. as one Slurm job
    array. When a task raises, the tasks not yet finished are cancelled (where the executor
    allows it) and the exception propagates as the executor delivers it.
    """
    if type(executor).__module__.split(".")[0] == "submitit":
        with executor.batch():
            futures = [executor.submit(fn, *args) for args in calls]
    else:
        futures = [executor.submit(fn, *args) for args in calls]
    try:
        return [f.result() for f in futures]
    except BaseException:
        for f in futures:
            cancel = getattr(f, "cancel", None)
            if callable(cancel):
                cancel()
        raise


def join(parts: list) -> Any:
    """The chunks' results joined along the points: numpy arrays concatenated on their first
    axis, lists concatenated, dicts (same keys in every chunk) joined key by key."""
    first = parts[0]
    if isinstance(first, dict):
        for p in parts[1:]:
            if list(p) != list(first):
                raise RuntimeError(f"chunks with different columns: {list(first)} and {list(p)}")
        return {k: join([p[k] for p in parts]) for k in first}
    if isinstance(first, np.ndarray):
        return np.concatenate(parts, axis=0)
    if isinstance(first, list):
        return [x for p in parts for x in p]
    raise TypeError(f"cannot join chunks of {type(first).__name__}")


def _task_scene(text: str, file: str, symbols: list) -> Scene:
    """The scene a task solves, rebuilt from its text (named as the caller's was)."""
    return Scene.from_toml(text, symbols=symbols or None, file=file)


def sweep_task(text: str, file: str, symbols: list, items: list, exact: bool,
               law: Optional[str], threads: Optional[int], shard: tuple[int, int]) -> dict:
    """One chunk of a sweep, on a worker: the columns of shard ``shard = (i, n)``."""
    return _native.sweep(_task_scene(text, file, symbols), items, exact, law, threads, shard)


def batch_task(text: str, file: str, symbols: list, pairs: list, law: Optional[str],
               offset: int) -> dict:
    """One chunk of a batch, on a worker: points ``offset …`` of the whole batch."""
    pairs = [(path, np.asarray(v, dtype=float).tolist()) for path, v in pairs]
    return _native.solve_batch(_task_scene(text, file, symbols), pairs, law, offset)


def sweep(scene: Scene, items: list, exact: bool, law: Optional[str], threads: Optional[int],
          executor: Any, chunk: Optional[int]) -> dict:
    """A sweep's columns, its chunks solved on ``executor``. Checked here first, as the
    in-process sweep checks it (an empty shard: the scene, the paths, both ends of every
    range, the corners), so bad input raises before any task is submitted."""
    points = math.prod(int(count) for _, _, _, count in items)
    # Shard 1 of P + 1 is empty: the check, and nothing solved.
    _native.sweep(scene, items, exact, law, threads, (1, points + 1))
    n = chunk_count(executor, points, chunk)
    calls = [(scene.toml, scene.file, scene.symbols, items, exact, law, threads, (i, n))
             for i in range(1, n + 1)]
    return join(gather(executor, sweep_task, calls))


def solve_batch(scene: Scene, pairs: list, law: Optional[str], executor: Any,
                chunk: Optional[int]) -> dict:
    """A batch's arrays, its chunks solved on ``executor``. The scene, the paths and the law
    are checked here first (a batch of no points), so bad input raises before any task is
    submitted; a value that makes the scene invalid raises from its task, naming its point
    by its index in the whole batch."""
    lengths = {len(v) for _, v in pairs}
    if len(lengths) > 1:
        # Arrays of different lengths: the native batch refuses them before solving anything.
        return _native.solve_batch(scene, [(p, v.tolist()) for p, v in pairs], law)
    empty = _native.solve_batch(scene, [(p, []) for p, _ in pairs], law)
    points = lengths.pop() if lengths else 0
    if points == 0:
        return empty
    n = chunk_count(executor, points, chunk)
    calls = []
    for i in range(1, n + 1):
        lo, hi = block(i, n, points)
        calls.append((scene.toml, scene.file, scene.symbols, [(p, v[lo:hi]) for p, v in pairs],
                      law, lo))
    return join(gather(executor, batch_task, calls))
