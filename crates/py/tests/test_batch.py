"""Many simulations in one call: the same numbers as one simulation at a time, whatever
the thread count; progress reported; Ctrl-C stops the call and leaves the interpreter
working; two Python threads can run batches at once (the GIL is released)."""

import os
import signal
import threading

import numpy as np
import pytest

import slipload

KEYS = ["peak_drift", "peak_drift_ratio", "peak_abs_acceleration", "residual_drift", "peak_slip"]


@pytest.fixture(scope="module")
def suite():
    return slipload.synthetic_suite(count=3, duration=4.0)


@pytest.fixture(scope="module")
def designs():
    return np.array([[0.0, 0.0, 0.0], [5e5, 4e5, 2e5], [2e6, 2e6, 2e6]])


def test_batch_designs_is_one_simulation_per_design_and_record(suite, designs):
    scene = slipload.load_scene()
    b = slipload.batch_designs(scene, suite, designs, outputs=["energies"], progress=False)
    assert b["peak_drift"].shape == (3, 3, 3)
    assert b["peak_base_shear"].shape == (3, 3)
    assert b["records"] == [r.name for r in suite]
    for d, loads in enumerate(designs):
        for r, rec in enumerate(suite):
            one = slipload.simulate(slipload.load_scene(record=rec).with_slip_loads(loads), outputs=["energies"])
            for k in KEYS:
                assert np.array_equal(b[k][d, r], getattr(one, k)), (k, d, r)
            assert b["peak_base_shear"][d, r] == one.peak_base_shear
            assert b["energy_friction"][d, r] == one.energy["friction"]
            assert np.array_equal(b["transitions"][d, r], one.transitions.astype(float))
    # a bare frame dissipates nothing by friction
    assert np.all(b["energy_friction"][0] == 0.0)


def test_thread_count_does_not_change_a_bit(suite, designs):
    scene = slipload.load_scene()
    one = slipload.batch_designs(scene, suite, designs, threads=1, progress=False)
    two = slipload.batch_designs(scene, suite, designs, threads=2, progress=False)
    for k in KEYS + ["peak_base_shear", "transitions"]:
        assert np.array_equal(one[k], two[k]), k


def test_batch_of_scenes_keeps_order_and_numbers(suite):
    scenes = [slipload.load_scene(record=r) for r in suite]
    results = slipload.batch(scenes, outputs=[], progress=False)
    for s, res in zip(scenes, results):
        assert np.array_equal(res.peak_drift, slipload.simulate(s, outputs=[]).peak_drift)


def test_progress_reaches_the_total(suite, designs):
    seen = []
    slipload.batch_designs(slipload.load_scene(), suite, designs, progress=lambda p, d, t: seen.append((p, d, t)))
    assert seen, "the callback was called"
    phase, done, total = seen[-1]
    assert (phase, done, total) == ("simulate", 9, 9)
    assert all(d <= t for _, d, t in seen)


def test_a_callback_that_raises_stops_the_batch(suite, designs):
    class Stop(Exception):
        pass

    def stop(phase, done, total):
        raise Stop()

    with pytest.raises(Stop):
        slipload.batch_designs(slipload.load_scene(), suite, designs, progress=stop)


def test_ctrl_c_stops_a_long_batch_and_the_interpreter_lives():
    suite = slipload.synthetic_suite(count=10)
    designs = np.tile(np.array([[5e5, 4e5, 2e5]]), (400, 1)) * np.linspace(0.1, 2.0, 400)[:, None]
    seen = []

    def progress(phase, done, total):
        seen.append((done, total))
        if done > 0 and not fired.is_set():
            fired.set()
            # Ctrl-C as the terminal sends it: SIGINT to this process, main thread
            threading.Timer(0.05, lambda: os.kill(os.getpid(), signal.SIGINT)).start()

    fired = threading.Event()
    # Python's own Ctrl-C handler, as an interactive interpreter has it: a process a
    # non-interactive shell starts in the background (`cmd &` in a script, as some CI
    # runners start their jobs) inherits SIGINT ignored, and Python then installs no
    # handler, so the signal would never reach the watcher
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            slipload.batch_designs(slipload.load_scene(), suite, designs, progress=progress, threads=1)
    finally:
        signal.signal(signal.SIGINT, previous)
    done, total = seen[-1]
    assert total == 4000 and done < total, "stopped before the end"
    # the interpreter and the engine work on
    assert slipload.simulate(slipload.load_scene(duration=0.5)).steps > 0


def test_two_python_threads_run_batches_at_once(suite, designs):
    scene = slipload.load_scene()
    want = slipload.batch_designs(scene, suite, designs, threads=1, progress=False)
    got = [None, None]

    def run(i):
        got[i] = slipload.batch_designs(scene, suite, designs, threads=1, progress=False)

    ts = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for g in got:
        assert g is not None
        assert np.array_equal(g["peak_drift"], want["peak_drift"])
