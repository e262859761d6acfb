"""Studies from Python write exactly the files the command line writes — the same bytes
(journals compared as sets of lines: their order is completion order) — and resume,
fingerprint and refuse as the command line does."""

import json
import os
import pathlib

import pytest

import slipload

from conftest import ROOT, run_cli

STUDY = ROOT / "configs" / "study-slurm-check.json"


def folder(path: pathlib.Path):
    """name → bytes of every file (journals: sorted lines), the lock file left out."""
    out = {}
    for p in sorted(path.iterdir()):
        if p.name == ".slipload.lock" or not p.is_file():
            continue
        data = p.read_bytes()
        if p.suffix == ".jsonl":
            data = b"\n".join(sorted(data.splitlines()))
        out[p.name] = data
    return out


def same_folders(a: pathlib.Path, b: pathlib.Path):
    fa, fb = folder(a), folder(b)
    assert sorted(fa) == sorted(fb)
    differ = [n for n in fa if fa[n] != fb[n]]
    assert not differ, f"files that differ: {differ}"
    return fa


def long_study(tmp_path):
    """The study of STUDY with 400 sweep points (a sweep of seconds, long enough to stop or
    to meet part-way), written into tmp_path with its paths made absolute."""
    study = json.loads(STUDY.read_text())
    study["sweep"]["points"] = 400
    study["building"] = str(ROOT / "configs" / "benchmark-3story.json")
    for s in study["suites"]:
        if "records" in s:
            s["records"] = [str((STUDY.parent / r).resolve()) for r in s["records"]]
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    return path


@pytest.fixture(scope="module")
def cli_optimized(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "opt"
    run_cli("optimize", STUDY, "--out", out, "--quiet")
    return out


def test_optimize_writes_the_cli_bytes(tmp_path, cli_optimized):
    out = tmp_path / "opt"
    report = slipload.optimize(str(STUDY), out, progress=False)
    files = same_folders(out, cli_optimized)
    # two suites: the drift profiles and the scatter per suite, none over both
    assert "design-table.json" in files and "convergence.svg" in files
    assert "drift-profiles-near-fault-0.4g.png" in files and "drift-profiles.png" not in files
    # the report is the files' content, as Python objects
    assert report.optimum == json.loads((out / "optimum.json").read_text())
    assert [r["design"] for r in report.design_table][0] == "optimum"
    assert report.candidates[0]["name"] == "optimum"
    assert report.details["work"]["sweep"][0] > 0
    per_suite = {f"{stem}-{suite}" for stem in ("drift-profiles", "records-scatter")
                 for suite in ("synthetic-0.4g-8s", "near-fault-0.4g")}
    assert set(report.figures) >= {"convergence"} | per_suite


def test_a_rerun_reuses_everything_and_writes_the_same_bytes(tmp_path, cli_optimized):
    out = tmp_path / "opt"
    slipload.optimize(str(STUDY), out, progress=False)
    again = slipload.optimize(str(STUDY), out, progress=False)
    assert all(run == 0 for run, _ in again.details["work"].values())
    same_folders(out, cli_optimized)


def test_an_interrupted_optimize_resumes_to_the_same_bytes(tmp_path, cli_optimized):
    out = tmp_path / "opt"

    def interrupt(phase, done, total):
        if phase == "refine" and done > 0:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        slipload.optimize(str(STUDY), out, progress=interrupt)
    # the sweep finished and is journalled; nothing of the summary files was half-written
    assert (out / "journal.jsonl").exists()
    assert not (out / "optimum.json").exists()
    assert not any(p.suffix == ".tmp" for p in out.iterdir())
    resumed = slipload.optimize(str(STUDY), out, progress=False)
    assert resumed.details["work"]["sweep"][0] == 0, "the sweep was not run again"
    same_folders(out, cli_optimized)


def test_threads_do_not_change_the_files(tmp_path, cli_optimized):
    out = tmp_path / "opt1"
    slipload.optimize(str(STUDY), out, threads=1, progress=False)
    same_folders(out, cli_optimized)


def test_sweep_shards_and_merge_write_the_cli_bytes(tmp_path):
    cli = tmp_path / "cli"
    run_cli("sweep", STUDY, "--out", cli, "--quiet")
    study = slipload.load_study(str(STUDY))
    whole = slipload.sweep(study, tmp_path / "whole", progress=False)
    assert whole.details["complete"] and whole.details["ran"] == whole.details["tasks"]
    same_folders(tmp_path / "whole", cli)
    for i in range(2):
        part = slipload.sweep(study, tmp_path / f"s{i}", shard=f"{i}/2", progress=False)
        assert not part.details["complete"]
    slipload.merge([tmp_path / "s0", tmp_path / "s1"], tmp_path / "merged")
    run_cli("merge", tmp_path / "s0", tmp_path / "s1", "--out", tmp_path / "cli-merged", "--quiet")
    same_folders(tmp_path / "merged", tmp_path / "cli-merged")
    with pytest.raises(slipload.InputError, match="named twice"):
        slipload.merge([tmp_path / "s0", tmp_path / "s0"], tmp_path / "m2")


def test_a_journal_of_another_study_is_refused(tmp_path):
    out = tmp_path / "o"
    slipload.sweep(str(STUDY), out, progress=False)
    other = json.loads(STUDY.read_text())
    other["sweep"]["seed"] = 1
    other["building"] = str(ROOT / "configs" / "benchmark-3story.json")
    for s in other["suites"]:
        if "records" in s:
            s["records"] = [str((STUDY.parent / r).resolve()) for r in s["records"]]
    with pytest.raises(slipload.InputError) as e:
        slipload.sweep(other, out, resume=True, progress=False)
    assert "fingerprint" in str(e.value) or "another study" in str(e.value)
    # fresh starts over
    again = slipload.sweep(other, out, fresh=True, progress=False)
    assert again.details["ran"] == again.details["tasks"]


def test_rank_and_table_write_the_cli_bytes(tmp_path, cli_optimized):
    cands = cli_optimized / "candidates.json"
    slipload.rank(str(STUDY), str(cands), tmp_path / "rank", bootstrap=20, progress=False)
    run_cli("rank", STUDY, "--designs", cands, "--out", tmp_path / "cli-rank", "--bootstrap", "20", "--quiet")
    same_folders(tmp_path / "rank", tmp_path / "cli-rank")
    designs = json.loads(cands.read_text())
    listed = slipload.rank(str(STUDY), designs, tmp_path / "rank-list", bootstrap=20, progress=False)
    assert folder(tmp_path / "rank-list") == folder(tmp_path / "rank")
    assert listed.ranking is not None
    slipload.table(str(STUDY), tmp_path / "table", period_scales=[1.0], intensity_scales=[0.8, 1.0], progress=False)
    run_cli("table", STUDY, "--period-scales", "1", "--intensity-scales", "0.8,1", "--out", tmp_path / "cli-table", "--quiet")
    same_folders(tmp_path / "table", tmp_path / "cli-table")
    with pytest.raises(slipload.InputError, match="given twice"):
        slipload.table(str(STUDY), tmp_path / "t2", intensity_scales=[1.0, 1.0], progress=False)


def test_ctrl_c_stops_a_sweep_and_resume_finishes_it(tmp_path):
    import signal
    import threading

    path = long_study(tmp_path)
    out = tmp_path / "sweep"
    seen = []
    fired = threading.Event()

    def progress(phase, done, total):
        seen.append(done)
        if done > 0 and not fired.is_set():
            fired.set()
            threading.Timer(0.02, lambda: os.kill(os.getpid(), signal.SIGINT)).start()

    with pytest.raises(KeyboardInterrupt):
        slipload.sweep(str(path), out, progress=progress, threads=1)
    journalled = len((out / "journal.jsonl").read_text().splitlines())
    assert 0 < journalled < 402 * 5, "stopped part-way, every finished task journalled"
    assert not (out / "manifest.json").exists() or not (out / "responses.csv").exists()
    resumed = slipload.sweep(str(path), out, resume=True, progress=False)
    assert resumed.details["resumed"] >= journalled - 1
    run_cli("sweep", path, "--out", tmp_path / "cli", "--quiet")
    same_folders(out, tmp_path / "cli")


def test_a_tqdm_bar_when_asked(tmp_path, capsys):
    pytest.importorskip("tqdm")
    slipload.sweep(str(STUDY), tmp_path / "o", progress=True)
    assert "sweep" in capsys.readouterr().err


def test_two_threads_into_one_folder_the_second_is_refused_and_the_first_finishes(tmp_path):
    """One study folder, one writer, also between the threads of one process: while a
    sweep runs into a folder, a second sweep into it from another thread is refused at
    once (a FileError that says the folder is in use), and the first finishes with the
    bytes of a sweep that ran alone."""
    import threading
    import time

    path = long_study(tmp_path)
    out = tmp_path / "sweep"
    running = threading.Event()
    tried = threading.Event()
    first = {}

    def progress(phase, done, total):
        if 0 < done < total and not running.is_set():
            running.set()
            # the first run keeps simulating while its caller waits here
            tried.wait(timeout=120)

    def first_run():
        try:
            first["report"] = slipload.sweep(str(path), out, progress=progress, threads=1)
        except BaseException as e:  # reported below, in the test's own thread
            first["error"] = e

    t = threading.Thread(target=first_run)
    t.start()
    try:
        assert running.wait(timeout=300), "the first sweep reports progress"
        started = time.monotonic()
        with pytest.raises(slipload.FileError, match="in use"):
            slipload.sweep(str(path), out, progress=False, threads=1)
        assert time.monotonic() - started < 30, "refused at once, not after waiting"
    finally:
        tried.set()
        t.join(timeout=600)
    assert "error" not in first, first.get("error")
    assert first["report"].details["complete"]
    run_cli("sweep", path, "--out", tmp_path / "alone", "--quiet")
    same_folders(out, tmp_path / "alone")


def test_fresh_keeps_the_users_files_and_names_them(tmp_path):
    out = tmp_path / "o"
    slipload.sweep(str(STUDY), out, progress=False)
    (out / "notes.txt").write_text("mine")
    again = slipload.sweep(str(STUDY), out, fresh=True, progress=False)
    assert again.details["kept"] == ["notes.txt"]
    assert "journal.jsonl" in again.details["removed"]
    assert (out / "notes.txt").read_text() == "mine"
    # a file under an output name that slipload did not write is never overwritten
    (out / "rank.md").write_text("my ranking")
    with pytest.raises(slipload.FileError, match="did not write"):
        slipload.sweep(str(STUDY), out, fresh=True, progress=False)
    assert (out / "rank.md").read_text() == "my ranking"


def test_the_design_table_frame_has_one_number_per_cell(cli_optimized):
    pd = pytest.importorskip("pandas")
    text = (cli_optimized / "design-table.json").read_text()
    report = slipload.StudyReport({"out": str(cli_optimized), "files": {"design-table.json": text}})
    frame = report.design_table_frame()
    table = json.loads(text)
    floors, rows = table["damper_floors"], table["rows"]
    storeys = len(rows[0]["drift_ratio_mean"])
    assert list(frame.index) == [r["design"] for r in rows]
    for column in frame.columns:
        assert not any(isinstance(v, (list, tuple, dict)) for v in frame[column]), column
    # per dissipator: one column per floor that carries one, named by that floor
    for key in ("slip_load_kn", "ratio_to_floor_weight", "ratio_to_weight_above"):
        assert [c for c in frame.columns if c.startswith(key + "_")] == [f"{key}_floor_{f}" for f in floors]
    # per storey: one column per storey
    for key in ("drift_ratio_mean", "drift_ratio_p84", "drift_ratio_max", "stroke_max"):
        assert [c for c in frame.columns if c.startswith(key + "_")] == [f"{key}_storey_{i}" for i in range(1, storeys + 1)]
    for r in rows:
        for k, f in enumerate(floors):
            assert frame.loc[r["design"], f"slip_load_kn_floor_{f}"] == r["slip_load_kn"][k]
        assert frame.loc[r["design"], f"drift_ratio_mean_storey_{storeys}"] == r["drift_ratio_mean"][-1]
        assert frame.loc[r["design"], "objective"] == r["objective"]
    # the same numbers as the CSV the command line wrote, column by column
    csv = pd.read_csv(cli_optimized / "design-table.csv").set_index("design")
    for f in floors:
        assert list(frame[f"slip_load_kn_floor_{f}"]) == list(csv[f"slip_load_kN_{f}"])
    for i in range(1, storeys + 1):
        assert list(frame[f"stroke_max_storey_{i}"]) == list(csv[f"stroke_max_m_{i}"])


def test_a_study_warns_what_the_command_line_warns():
    """A base-shear limit of 5000 (meant as kN, read as N) is warned about as the command
    line warns it ("did you mean kN?"), naming the field; a plausible one is not."""
    study = json.loads(STUDY.read_text())
    study["building"] = str(ROOT / "configs" / "benchmark-3story.json")
    for s in study["suites"]:
        if "records" in s:
            s["records"] = [str((STUDY.parent / r).resolve()) for r in s["records"]]

    def with_limit(max_n):
        s = json.loads(json.dumps(study))
        s["suites"][0]["limits"] = {"criteria": [
            {"metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02},
            {"metric": "base_shear", "statistic": "mean", "max": max_n}]}
        return s

    with pytest.warns(UserWarning, match=r"suites\[0\]\.limits\.criteria\[1\]\.max: .*did you mean kN"):
        loaded = slipload.load_study(with_limit(5000.0))
    assert any("did you mean kN" in w for w in loaded.warnings)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert slipload.load_study(with_limit(5.0e6)).warnings == []
