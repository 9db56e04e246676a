"""solve_batch and sweep on executors (executor=, chunk=): a process pool, a thread pool and a
Dask local cluster give the in-process result bit for bit; bad input raises before anything
is submitted; a task's exception propagates."""

import multiprocessing
import threading
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from fractions import Fraction

import numpy as np
import pytest

import inertance
from conftest import BAR, ROOT

CRADLE = ROOT / "examples" / "cradle-3.toml"
COINCIDENT = BAR.read_text().replace("point = [0, 4, 0]", "point = [0, -2, 0]")


def assert_identical(a, b, where="result"):
    """Bit for bit: the same keys in the same order, arrays of the same dtype, shape and bytes
    (NaN included), lists of the same values of the same types (Fraction stays Fraction)."""
    assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, dict):
        assert list(a) == list(b), f"{where}: keys {list(a)} != {list(b)}"
        for k in a:
            assert_identical(a[k], b[k], f"{where}[{k!r}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, f"{where}: {a.dtype}{a.shape} != {b.dtype}{b.shape}"
        assert a.tobytes() == b.tobytes(), f"{where}: values differ"
    elif isinstance(a, tuple):
        assert len(a) == len(b), f"{where}: {len(a)} != {len(b)} items"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_identical(x, y, f"{where}[{i}]")
    elif isinstance(a, list):
        assert len(a) == len(b), f"{where}: {len(a)} != {len(b)} items"
        for i, (x, y) in enumerate(zip(a, b)):
            assert type(x) is type(y) and x == y, f"{where}[{i}]: {x!r} != {y!r}"
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


class Counting(ThreadPoolExecutor):
    """A thread pool that counts the tasks submitted to it."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.submitted = 0
        self.lock = threading.Lock()

    def submit(self, fn, /, *args, **kwargs):
        with self.lock:
            self.submitted += 1
        return super().submit(fn, *args, **kwargs)


@pytest.fixture(scope="module")
def processes():
    # The default context: on Linux before Python 3.14, fork — the workers are forked after the
    # in-process calls have started the parallel calls' thread pool, whose threads a forked
    # child does not have (the bindings give it a pool of its own).
    with ProcessPoolExecutor(2) as pool:
        yield pool


def _in_a_fork(queue):
    """A forked child's batch and sweep, sent back to its parent."""
    queue.put((inertance.solve_batch(BAR, {"contact[1].k": K}),
               inertance.sweep(BAR, {"contact[1].k": (0, 1, 50)}, frame=False)))


def test_a_process_forked_after_parallel_calls_solves_in_parallel():
    # The parent's parallel calls start a thread pool; a forked child (a fork process pool's
    # worker) has none of its threads, and used to wait on them forever.
    here = (inertance.solve_batch(BAR, {"contact[1].k": K}),
            inertance.sweep(BAR, {"contact[1].k": (0, 1, 50)}, frame=False))
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    child = context.Process(target=_in_a_fork, args=(queue,))
    child.start()
    try:
        there = queue.get(timeout=120)
    finally:
        child.join(5)
        if child.is_alive():
            child.terminate()
    assert_identical(here, there)


def test_a_forkserver_pool():
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("forkserver")) as pool:
        vary = {"contact[1].k": K}
        assert_identical(inertance.solve_batch(BAR, vary),
                         inertance.solve_batch(BAR, vary, executor=pool, chunk=30))


@pytest.fixture(scope="module")
def threads():
    with Counting(2) as pool:
        yield pool


@pytest.fixture(params=["processes", "threads"])
def executor(request):
    return request.getfixturevalue(request.param)


# k over [0, 1] and ω over a range where the simultaneous answer turns tensile: statuses vary.
K = np.linspace(0, 1, 101)
OMEGA = np.linspace(0.2, 1.2, 101)


@pytest.mark.parametrize("chunk", [None, 1, 7, 100, 101, 1000])
def test_batch_on_an_executor_equals_the_in_process_batch(executor, chunk):
    vary = {"contact[1].k": K, "body.angular_velocity[2]": OMEGA}
    here = inertance.solve_batch(BAR, vary)
    assert {"ok"} < set(here["status"])  # more than one status: the rows must line up
    there = inertance.solve_batch(BAR, vary, executor=executor, chunk=chunk)
    assert_identical(here, there)
    assert there["newton"]["impulses"].shape == (101, 2)


def test_batch_of_a_system_and_of_singular_points(executor):
    k = np.linspace(0.1, 1, 23)
    here = inertance.solve_batch(CRADLE, {"contact[1].k": k})
    there = inertance.solve_batch(CRADLE, {"contact[1].k": k}, executor=executor, chunk=5)
    assert set(there["newton"]["bodies"]) == set(inertance.Scene.load(CRADLE).bodies)
    assert_identical(here, there)
    here = inertance.solve_batch(COINCIDENT, {"contact[1].k": k})
    there = inertance.solve_batch(COINCIDENT, {"contact[1].k": k}, executor=executor, chunk=4)
    assert there["status"] == ["singular"] * 23 and np.isnan(there["newton"]["impulses"]).all()
    assert_identical(here, there)


def test_default_chunks_are_four_per_worker(threads):
    before = threads.submitted
    inertance.solve_batch(BAR, {"contact[1].k": K}, executor=threads)
    assert threads.submitted - before == 8
    inertance.sweep(BAR, {"contact[1].k": (0, 1, 5)}, executor=threads)
    assert threads.submitted - before == 8 + 5  # never more chunks than points
    inertance.sweep(BAR, {"contact[1].k": (0, 1, 50)}, executor=threads, chunk=7)
    assert threads.submitted - before == 8 + 5 + 8  # ⌈50 / 7⌉


def test_batch_of_no_points_submits_nothing(threads):
    before = threads.submitted
    here = inertance.solve_batch(BAR, {"contact[1].k": []})
    there = inertance.solve_batch(BAR, {"contact[1].k": []}, executor=threads)
    assert_identical(here, there)
    assert threads.submitted == before


@pytest.mark.parametrize("chunk", [None, 3, 7, 50])
def test_sweep_of_one_key_on_an_executor_equals_the_in_process_sweep(executor, chunk):
    vary = {"contact[1].k": (0, 1, 50)}
    here = inertance.sweep(BAR, vary, frame=False)
    there = inertance.sweep(BAR, vary, frame=False, executor=executor, chunk=chunk)
    assert list(there["point"]) == list(range(50))
    assert_identical(here, there)


@pytest.mark.parametrize("chunk", [4, 11])
def test_exact_sweep_of_two_keys_on_an_executor_equals_the_in_process_sweep(executor, chunk):
    # 5 × 7 = 35 points, start and stop exact ("1/3"), the exact columns as Fraction.
    vary = {"contact[0].k": (0, "1/3", 5), "body.angular_velocity[2]": ("2/5", "6/5", 7)}
    here = inertance.sweep(BAR, vary, exact=True, frame=False)
    there = inertance.sweep(BAR, vary, exact=True, frame=False, executor=executor, chunk=chunk)
    assert_identical(here, there)
    assert list(there["point"]) == list(range(35))
    assert there["contact[0].k_exact"][7] == Fraction(1, 12)
    assert isinstance(there["newton_P1_exact"][0], Fraction)
    assert len(set(there["status"])) > 1


def test_sweep_with_singular_points_and_as_a_frame(threads):
    vary = {"contact[1].k": (0, 1, 9)}
    here = inertance.sweep(COINCIDENT, vary, frame=False)
    there = inertance.sweep(COINCIDENT, vary, frame=False, executor=threads, chunk=2)
    assert set(there["status"]) == {"singular"} and np.isnan(there["newton_P1"]).all()
    assert_identical(here, there)
    # The default return type (a DataFrame with pandas installed, else the dict) is kept.
    here = inertance.sweep(BAR, vary)
    there = inertance.sweep(BAR, vary, executor=threads, chunk=2)
    assert type(here) is type(there)
    if isinstance(here, dict):
        assert_identical(here, there)
    else:
        import pandas.testing
        pandas.testing.assert_frame_equal(here, there, check_exact=True)


def test_a_sweep_under_lzb_on_an_executor(threads):
    vary = {"contact[1].stiffness": (1, 4, 5)}
    bar = ROOT / "examples" / "bar-two-supports-lzb.toml"
    here = inertance.sweep(bar, vary, frame=False)
    there = inertance.sweep(bar, vary, frame=False, executor=threads, chunk=2)
    assert "order" in there
    assert_identical(here, there)


def test_bad_input_raises_before_anything_is_submitted(threads):
    before = threads.submitted
    with pytest.raises(inertance.SceneError) as here:
        inertance.sweep("name = 'x'\n[body]\nmass = -1\n", {"contact[0].k": (0, 1, 4)})
    with pytest.raises(inertance.SceneError) as there:
        inertance.sweep("name = 'x'\n[body]\nmass = -1\n", {"contact[0].k": (0, 1, 4)},
                        executor=threads)
    assert str(there.value) == str(here.value)
    for call in (inertance.sweep, inertance.solve_batch):
        vary = {"contact[9].k": (0, 1, 4)} if call is inertance.sweep else {"contact[9].k": [0.5]}
        with pytest.raises(inertance.SweepError) as here:
            call(BAR, vary)
        with pytest.raises(inertance.SweepError) as there:
            call(BAR, vary, executor=threads)
        assert str(there.value) == str(here.value) and "contact[9].k" in str(there.value)
    # A range that leaves the scene invalid at its end, arrays of different lengths, a bad law.
    with pytest.raises(inertance.SweepError, match="1.5"):
        inertance.sweep(BAR, {"contact[1].k": (0, 1.5, 4)}, executor=threads)
    with pytest.raises(inertance.SweepError, match="every varied number needs one value"):
        inertance.solve_batch(BAR, {"contact[1].k": [0.5], "body.mass": [1, 2]}, executor=threads)
    with pytest.raises(ValueError, match="law"):
        inertance.solve_batch(BAR, {"contact[1].k": [0.5]}, law="nope", executor=threads)
    assert threads.submitted == before
    with pytest.raises(ValueError, match="at least 1 point"):
        inertance.sweep(BAR, {"contact[1].k": (0, 1, 4)}, executor=threads, chunk=0)
    with pytest.raises(ValueError, match="give executor= too"):
        inertance.solve_batch(BAR, {"contact[1].k": [0.5]}, chunk=10)


def test_an_exception_in_a_task_propagates_with_its_point(executor):
    # k = 1.5 makes the scene invalid at point 57 only: the task of the chunk holding it
    # raises, and the error names the point by its index in the whole batch.
    k = np.full(80, 0.5)
    k[57] = 1.5
    with pytest.raises(inertance.SweepError) as here:
        inertance.solve_batch(BAR, {"contact[1].k": k})
    with pytest.raises(inertance.SweepError) as there:
        inertance.solve_batch(BAR, {"contact[1].k": k}, executor=executor, chunk=10)
    assert there.value.point == here.value.point == 57
    assert there.value.key == "contact[1].k" and there.value.value == "1.5"
    assert str(there.value) == str(here.value)


def test_on_a_dask_local_cluster():
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        executor = client.get_executor()
        vary = {"contact[1].k": K, "body.angular_velocity[2]": OMEGA}
        with distributed.get_task_stream(client) as tasks:
            there = inertance.solve_batch(BAR, vary, executor=executor)
        assert_identical(inertance.solve_batch(BAR, vary), there)
        # By default four chunks per worker thread: 2 workers × 1 thread.
        assert len(tasks.data) == 8
        with distributed.get_task_stream(client) as tasks:
            there = inertance.solve_batch(BAR, vary, executor=executor, chunk=9)
        assert_identical(inertance.solve_batch(BAR, vary), there)
        # ⌈101 / 9⌉ = 12 tasks, each run by one of the cluster's workers.
        assert len(tasks.data) == 12
        assert {t["worker"] for t in tasks.data} <= set(client.scheduler_info()["workers"])
        grid = {"contact[0].k": (0, "1/3", 5), "body.angular_velocity[2]": ("2/5", "6/5", 7)}
        assert_identical(inertance.sweep(BAR, grid, exact=True, frame=False),
                         inertance.sweep(BAR, grid, exact=True, frame=False, executor=executor,
                                         chunk=6))
        assert len(client.scheduler_info()["workers"]) == 2
        k = np.full(30, 0.5)
        k[21] = 1.5
        with pytest.raises(inertance.SweepError) as e:
            inertance.solve_batch(BAR, {"contact[1].k": k}, executor=executor, chunk=4)
        assert e.value.point == 21
